// Wall solve (issue 6): a D = 10 tube along z in a 12 x 12 x 8 periodic box, <u> = e_z, Ewald
// tolerance 1e-8, GMRES to 1e-6 with the near-field sparse-LU preconditioner. Set-up (gmsh
// mesh excluded: elements, near field, Ewald plan, LU) and one solve, timed separately;
// counters: triangles, GMRES iterations.
//   build/bin/bench_wall                       h = 0.5 (~2,400 triangles)
//   build/bin/bench_wall --benchmark_filter=/1 h = 0.15 (~26,000 triangles; minutes)
// Argument: element size index (0: h = 0.5, 1: h = 0.15).
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>

#include "geometry/vessel.h"
#include "libsolver/wall/wall_solver.h"

using namespace rbcflow;

namespace {

void BM_WallTube(benchmark::State& state) {
  TubeSpec spec;
  spec.diameter = 10.0;
  spec.box = Eigen::Vector3d(12.0, 12.0, 8.0);
  spec.element_size = state.range(0) == 0 ? 0.5 : 0.15;
  const VesselMesh wall = tube(spec);
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    auto e = std::make_shared<const WallElements>(wall);
    WallSolver solver(WallOperator(e, e->wall.surface.points, PeriodicBox(spec.box), 1e-8, nullptr,
                                   WallOperator::RealSpace::assembled));
    const auto t1 = std::chrono::steady_clock::now();
    const WallSolution s = solver.solve(Eigen::RowVector3d(0, 0, 1).replicate(e->num_nodes(), 1), 1.0);
    const auto t2 = std::chrono::steady_clock::now();
    state.counters["setup_s"] = std::chrono::duration<double>(t1 - t0).count();
    state.counters["solve_s"] = std::chrono::duration<double>(t2 - t1).count();
    state.counters["triangles"] = e->num_triangles();
    state.counters["iterations"] = s.gmres.iterations;
  }
}

}  // namespace

BENCHMARK(BM_WallTube)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK_MAIN();
