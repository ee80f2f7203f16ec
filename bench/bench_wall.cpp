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
#include <numbers>
#include <random>

#include "geometry/vessel/vessel.h"
#include "libsolver/common/memory_report.h"
#include "libsolver/spme/ewald_parameters.h"
#include "libsolver/stepper/wall_coupling.h"
#include "libsolver/wall/near_field.h"
#include "libsolver/wall/symmetric_block_matrix.h"
#include "libsolver/wall/wall_real_space.h"
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

// The assembled near-field + real-space part of tube27's wall solve (D = 6, box 6.6 x 6.6 x
// 13.33, h = 0.25, Ewald tolerance 1e-7 as the solve asks for 1e-6) applied to a nodal
// density: argument 0 as a scalar Eigen sparse matrix (row-major, OpenMP over rows), 1 as
// symmetric 3x3 blocks (SymmetricBlockMatrix, what WallOperator keeps).
//   build/bin/bench_wall --benchmark_filter=WallProduct
void BM_WallProduct(benchmark::State& state) {
  static const auto matrix = [] {
    const Eigen::Vector3d side(6.6, 6.6, 13.33);
    const WallElements e(tube(TubeSpec{6.0, 2, side, 0.25}));
    const PeriodicBox box(side);
    const PointField& nodes = e.wall.surface.points;
    const EwaldChoice c =
        choose_ewald_parameters(EwaldKernel::stokeslet, 1e-7, box, e.points.rows(), nodes.rows(), kAssembledRealSpace);
    PointField sources(e.points.rows(), 3), targets(nodes.rows(), 3);
    for (Eigen::Index i = 0; i < sources.rows(); ++i) sources.row(i) = box.wrap(e.points.row(i).transpose()).transpose();
    for (Eigen::Index i = 0; i < targets.rows(); ++i) targets.row(i) = box.wrap(nodes.row(i).transpose()).transpose();
    const NeighborList pairs(box, c.parameters.cutoff, sources, targets);
    return Eigen::SparseMatrix<double, Eigen::RowMajor>(near_field(e, nodes).correction +
                                                        wall_real_space_matrix(e, pairs, c.parameters.xi));
  }();
  const Eigen::VectorXd f = Eigen::VectorXd::Random(matrix.cols());
  Eigen::VectorXd y;
  if (state.range(0) == 0) {
    for (auto _ : state) benchmark::DoNotOptimize(y = matrix * f);
  } else {
    const SymmetricBlockMatrix blocks(matrix);
    for (auto _ : state) benchmark::DoNotOptimize(y = blocks * f);
  }
  state.counters["nonzeros"] = static_cast<double>(matrix.nonZeros());
}

// Three velocities at the wall nodes, each induced by `pairs` force-free pairs of point forces
// (free-space Stokeslets 0.5 apart, a stand-in for the cells') at random points of the lumen,
// a tube of radius `radius` about (c, c, z) periodic along z with period `length`.
std::vector<PointField> point_force_pairs(const PointField& nodes, double c, double radius, double length, long pairs) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  std::vector<PointField> velocities(3, PointField::Zero(nodes.rows(), 3));
  for (PointField& v : velocities) {
    for (long k = 0; k < pairs; ++k) {
      const double r = radius * std::sqrt(u(rng)), phi = 2 * std::numbers::pi * u(rng);
      const Eigen::Vector3d x(c + r * std::cos(phi), c + r * std::sin(phi), length * u(rng));
      const Eigen::Vector3d f(g(rng), g(rng), g(rng)), d = 0.5 * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
      for (Eigen::Index i = 0; i < nodes.rows(); ++i) {
        for (const double sign : {1.0, -1.0}) {
          Eigen::Vector3d rv = nodes.row(i).transpose() - x - (sign > 0 ? Eigen::Vector3d::Zero() : d);
          rv[2] -= length * std::round(rv[2] / length);  // the nearest image along the axis
          const double rn = rv.norm();
          v.row(i) += sign * (f / rn + rv * rv.dot(f) / (rn * rn * rn)).transpose() / (8 * std::numbers::pi);
        }
      }
    }
  }
  return velocities;
}

// Set-up of a WallCoupling (operator, preconditioner, the three unit-<u> seed solves) and the
// mean iterations and seconds of later solves from zero for `velocities`.
void time_wall_solves(benchmark::State& state, const std::shared_ptr<const WallElements>& e, const Eigen::Vector3d& side,
                      const WallSolveOptions& options, const std::vector<PointField>& velocities) {
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    WallCoupling wall(e, PeriodicBox(side), 1e-6, options);
    const auto t1 = std::chrono::steady_clock::now();
    double iterations = 0;
    for (const PointField& v : velocities) iterations += wall.solve(v, {}).gmres.iterations;
    const auto t2 = std::chrono::steady_clock::now();
    state.counters["setup_s"] = std::chrono::duration<double>(t1 - t0).count();
    state.counters["solve_s"] = std::chrono::duration<double>(t2 - t1).count() / velocities.size();
    state.counters["nodes"] = static_cast<double>(e->num_nodes());
    state.counters["iterations"] = iterations / velocities.size();
    MemoryReport memory;
    wall.report_memory(memory);
    for (const MemoryReport::Item& i : memory.items()) {
      if (i.name == "wall recycled space") state.counters["directions"] = i.bytes / (48.0 * e->num_nodes());
      if (i.name == "wall preconditioner (LU)") state.counters["lu_MB"] = i.bytes / 1e6;
    }
  }
}

// The wall of data/cases/tube_1000_cells.toml (D = 12 tube, box 12.6 x 12.6 x L, h = 0.4, Ewald
// tolerance 1e-6, GMRES to 1e-6) with the period of K cells at its hematocrit, L = 123.56 K /
// 1000, and the recycled space's capacity R (WallSolveOptions::recycle): set-up (operator,
// LU, the three unit-<u> seed solves), then solves from zero for the velocity that 4 K force-free
// pairs of point forces in the lumen (free-space Stokeslets 0.5 apart, a stand-in for the
// cells') induce at the nodes. Counters: wall nodes, directions kept, iterations of each later
// solve (mean). R = 900 bounds nothing: the seeds stop before it.
//   build/bin/bench_wall --benchmark_filter=LongTube         arguments K, R (about 12 minutes)
//   build/bin/bench_wall --benchmark_filter=LongTube/1000    the 1,000-cell tube's wall
void BM_LongTube(benchmark::State& state) {
  const double length = 123.56 * static_cast<double>(state.range(0)) / 1000.0;
  const Eigen::Vector3d side(12.6, 12.6, length);
  const auto e = std::make_shared<const WallElements>(tube(TubeSpec{12.0, 2, side, 0.4}));
  WallSolveOptions options;
  options.recycle = static_cast<int>(state.range(1));
  time_wall_solves(state, e, side, options, point_force_pairs(e->wall.surface.points, 6.3, 5.0, length, 4 * state.range(0)));
}

// The wall of bench_step's tubeK (data/cases/tube_27_cells.toml's D = 6 tube, h = 0.25, box
// 6.6 x 6.6 x 13.33 K / 27, Ewald tolerance 1e-6, GMRES to 1e-6, recycled space 300) with the
// preconditioner's blocks of B nodes (wall_preconditioner.h; 0: one block): set-up and later
// solves as LongTube's, for 4 K pairs of point forces; counters as LongTube's and lu_MB, the
// L and U of the blocks.
//   build/bin/bench_wall --benchmark_filter=WallBlocks       arguments K, B (about 20 minutes)
void BM_WallBlocks(benchmark::State& state) {
  const double length = 13.33 * static_cast<double>(state.range(0)) / 27.0;
  const Eigen::Vector3d side(6.6, 6.6, length);
  const auto e = std::make_shared<const WallElements>(tube(TubeSpec{6.0, 2, side, 0.25}));
  WallSolveOptions options;
  if (state.range(1) > 0) options.preconditioner_block_nodes = static_cast<int>(state.range(1));
  else options.preconditioner_block_nodes = static_cast<int>(e->num_nodes());
  time_wall_solves(state, e, side, options, point_force_pairs(e->wall.surface.points, 3.3, 2.5, length, 4 * state.range(0)));
  state.counters["blocks"] = wall_preconditioner_blocks(e->num_nodes(), options.preconditioner_block_nodes);
}

}  // namespace

BENCHMARK(BM_LongTube)
    ->ArgsProduct({{125, 512, 1000}, {150, 300, 900}})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK(BM_WallBlocks)
    ->ArgsProduct({{27, 125}, {0, 12000, 6000, 3000, 1500, 750, 500, 250, 100}})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
BENCHMARK(BM_WallTube)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_WallProduct)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
