// Membrane traction of one biconcave cell (issue: membrane mechanics).
//   build/bin/bench_membrane
#include <benchmark/benchmark.h>

#include <random>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/membrane/membrane_force.h"

using namespace rbcflow;

// Skalak law with bending, parameters (35), on a deformed red cell of order N, de-aliased on M.
static void BM_MembraneTraction(benchmark::State& state) {
  const int N = static_cast<int>(state.range(0)), M = static_cast<int>(state.range(1));
  const SHSurface ref = make_biconcave(N);
  const Membrane membrane(ref, CellGrids::make(N, M),
                          {std::make_shared<SkalakLaw>(12.4, 200.0), 0.0669});
  SHCoeffs x = ref.coeffs();
  std::mt19937 gen(1);
  std::normal_distribution<double> nd;
  for (int i = 0; i < 3 * 25; ++i) x.values()(i % (N * N), i % 3) += 0.003 * nd(gen);
  for (auto _ : state) {
    MembraneState s = membrane.compute(x);
    benchmark::DoNotOptimize(s.traction.values().data());
  }
}
BENCHMARK(BM_MembraneTraction)->Args({16, 32})->Args({16, 48})->Args({32, 64})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
