// Spherical-harmonic transforms and cell geometry (issue: foundation).
//   build/bin/bench_sph_transform [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "geometry/surface/reference_shapes.h"
#include "geometry/sph/sph_transform.h"

using namespace rbcflow;

// Forward + inverse transform of a 3-vector field on the N x 2N Gauss grid.
static void BM_TransformRoundTrip3(benchmark::State& state) {
  const int N = static_cast<int>(state.range(0));
  const SHTransform t = SHTransform::gauss(N, 0);
  SHCoeffs c(N, 3);
  c.values().setRandom();
  Eigen::MatrixXd grid(t.grid().size(), 3);
  for (auto _ : state) {
    t.synthesize(c, 0, 0, grid);
    c = t.analyze(grid);
    benchmark::DoNotOptimize(c.values().data());
  }
}
BENCHMARK(BM_TransformRoundTrip3)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);

// Full geometry of one cell (order N) on the de-aliasing M x 2M grid.
static void BM_CellGeometryOnDealiasGrid(benchmark::State& state) {
  const int N = static_cast<int>(state.range(0)), M = static_cast<int>(state.range(1));
  const SHTransform t = SHTransform::gauss(M, 2);
  const SHSurface cell = make_biconcave(N);
  for (auto _ : state) {
    SurfaceGeometry g = cell.geometry(t);
    benchmark::DoNotOptimize(g.mean_curvature.data());
  }
}
BENCHMARK(BM_CellGeometryOnDealiasGrid)->Args({16, 48})->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
