// Periodic single- and double-layer products by Ewald splitting (issue 4): N random points in
// the unit cube (sources = targets), tolerance 1e-6, parameters from choose_ewald_parameters,
// the plan (FFTW_ESTIMATE plans, stencils, neighbour lists) built once outside the timed loop, as
// in a GMRES solve. Counters: the stages of one product in ms (real space, spreading, FFT,
// influence, interpolation), CPU time of all threads, the plan's setup time, and the chosen
// parameters. The 10^4 and 10^5 cases repeat 3 times (median reported): the development machine
// is shared.
//   build/bin/bench_spme --benchmark_filter=Layer/            10^4 and 10^5 points
//   build/bin/bench_spme --benchmark_filter=Million           10^6 points (minutes, ~10 GB)
// Arguments: points, OpenMP threads.
//   build/bin/bench_spme --benchmark_filter=GridTransform     one grid's forward + backward
//                                                            (GridTransformThousandCells: 1 GB)
// transforms with FFTW_ESTIMATE and FFTW_MEASURE plans, on tube27's grids (arguments: K for a
// K x K x 2K grid, density components, 1 = measured; all OpenMP threads; plan_ms: the planning).
//   build/bin/bench_spme --benchmark_filter=NeighborList      tube27's cell-cell lists (argument:
// the cutoff in thousandths)
//   build/bin/bench_spme --benchmark_filter=RealSpace         the real-space sums alone on tube27's
// cells, every pair's kernel computed (as in products without kept coefficients); pair_ns: wall
// time per listed pair (arguments: 0 single / 1 double layer, OpenMP threads)
//   build/bin/bench_spme --benchmark_filter=Tube27Cells       the same products on tube27's
// cells as the solver sees them: 27 red cells of data/cases/tube_27_cells.toml (seed 1), 512
// nodes each, stored cell by cell, with their normals (argument: OpenMP threads). Clustered and
// ordered, their pairs cost a fraction of the unit cube's random ones; pair_ns (first_pair_ns:
// the first product, which computes the coefficients the double layer keeps), node_ns and
// fft_ns are the costs per pair (as the model counts them: uniform density), per grid node
// and component, and per component and K log2 K of the cost model (ewald_parameters.cpp).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <mutex>
#include <random>
#include <vector>

#include "geometry/contact/cell_placement.h"
#include "geometry/sph/fftw_util.h"
#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"
#include "libsolver/spme/ewald_plan.h"
#include "libsolver/spme/neighbor_list.h"
#include "libsolver/spme/real_space_sum.h"

using namespace rbcflow;

namespace {

PointField random_field(int n, unsigned seed, bool unit_cube) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  PointField x(n, 3);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) x(i, d) = unit_cube ? u(gen) : g(gen);
  return x;
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Points, unit normals and the box of a product's benchmark.
struct ProductPoints {
  PeriodicBox box;
  PointField x, normals;
};

ProductPoints unit_cube_points(int n) {
  return {PeriodicBox(Eigen::Vector3d::Ones()), random_field(n, 1, true),
          random_field(n, 3, false).rowwise().normalized()};
}

// tube27's initial cells (bench/step_cases.cpp tube_cells(27)): nodes of the N = 16 Gauss grid.
ProductPoints tube27_cell_points() {
  const Eigen::Vector3d side(6.6, 6.6, 13.33);
  const VesselMesh vessel = tube(TubeSpec{6.0, 2, side, 0.25});
  PlacementSpec placement;
  placement.box = side;
  placement.count = 27;
  placement.gap = 0.05;
  placement.seed = 1;
  const SHSurface rbc = make_biconcave(16);
  const SHTransform transform = SHTransform::gauss(16);
  ProductPoints p{PeriodicBox(side), PointField(27 * 512, 3), PointField(27 * 512, 3)};
  int row = 0;
  for (const SHSurface& cell : placed_surfaces(rbc, place_cells(rbc, placement, &vessel).cells)) {
    const SurfaceGeometry g = cell.geometry(transform);
    p.x.middleRows(row, g.size()) = g.x;
    p.normals.middleRows(row, g.size()) = g.normal;
    row += g.size();
  }
  return p;
}

void run_product(benchmark::State& state, EwaldKernel kernel, const ProductPoints& points, int threads_arg) {
  const int n = static_cast<int>(points.x.rows());
  const int threads = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(threads_arg)));
  const PeriodicBox& box = points.box;
  const PointField& x = points.x;
  const PointField& normals = points.normals;
  const PointField f = random_field(n, 2, false);
  const EwaldChoice choice = choose_ewald_parameters(kernel, 1e-6, box, n);

  const auto start = std::chrono::steady_clock::now();
  EwaldPlan plan(std::make_shared<const SpmeGrid>(box, choice.parameters, FftPlanning::estimate),
                 x);
  const double setup =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  EwaldTimings total;
  double real_first = -1.0;  // the first product's real-space sum (the double layer's pair coefficients)
  const double cpu_start = process_cpu_seconds();
  for (auto _ : state) {
    PointField u =
        kernel == EwaldKernel::stokeslet ? plan.single_layer(f) : plan.double_layer(f, normals);
    benchmark::DoNotOptimize(u.data());
    const EwaldTimings& t = plan.timings();
    if (real_first < 0.0) real_first = t.real_space;
    total.real_space += t.real_space;
    total.smooth.spreading += t.smooth.spreading;
    total.smooth.fft += t.smooth.fft;
    total.smooth.influence += t.smooth.influence;
    total.smooth.interpolation += t.smooth.interpolation;
  }
  const double ms = 1e3 / static_cast<double>(state.iterations());
  state.counters["cpu_ms"] = (process_cpu_seconds() - cpu_start) * ms;  // all threads
  state.counters["real_ms"] = total.real_space * ms;
  state.counters["spread_ms"] = total.smooth.spreading * ms;
  state.counters["fft_ms"] = total.smooth.fft * ms;
  state.counters["influence_ms"] = total.smooth.influence * ms;
  state.counters["interp_ms"] = total.smooth.interpolation * ms;
  state.counters["setup_ms"] = 1e3 * setup;
  state.counters["K"] = choice.parameters.grid[0];
  state.counters["p"] = choice.parameters.order;
  state.counters["neighbours"] = choice.neighbours_per_target;
  state.counters["xi"] = choice.parameters.xi;
  // The cost model's units (ewald_parameters.cpp modelled_seconds), CPU time of one thread.
  const EwaldParameters& p = choice.parameters;
  const double in = kernel == EwaldKernel::stokeslet ? 3.0 : 6.0, nodes = std::pow(p.order, 3.0);
  const double grid_points = static_cast<double>(p.grid[0]) * p.grid[1] * p.grid[2];
  const double threads_used = static_cast<double>(state.range(threads_arg));
  const double model_pairs = n * choice.neighbours_per_target;
  state.counters["pair_ns"] = threads_used * 1e6 * state.counters["real_ms"] / model_pairs;
  state.counters["first_pair_ns"] = threads_used * 1e9 * real_first / model_pairs;
  state.counters["node_ns"] = threads_used * 1e6 * (state.counters["spread_ms"] + state.counters["interp_ms"]) /
                              (nodes * (in + 3.0) * n);
  state.counters["fft_ns"] = threads_used * 1e6 * state.counters["fft_ms"] / ((in + 3.0) * grid_points * std::log2(grid_points));
  omp_set_num_threads(threads);
}

void BM_SingleLayer(benchmark::State& state) {
  run_product(state, EwaldKernel::stokeslet, unit_cube_points(static_cast<int>(state.range(0))), 1);
}
void BM_DoubleLayer(benchmark::State& state) {
  run_product(state, EwaldKernel::stresslet, unit_cube_points(static_cast<int>(state.range(0))), 1);
}
void BM_SingleLayerMillion(benchmark::State& state) { BM_SingleLayer(state); }
void BM_DoubleLayerMillion(benchmark::State& state) { BM_DoubleLayer(state); }

const ProductPoints& tube27_cells() {
  static const ProductPoints points = tube27_cell_points();
  return points;
}
void BM_Tube27CellsSingleLayer(benchmark::State& state) {
  run_product(state, EwaldKernel::stokeslet, tube27_cells(), 0);
}
void BM_Tube27CellsDoubleLayer(benchmark::State& state) {
  run_product(state, EwaldKernel::stresslet, tube27_cells(), 0);
}

// The real-space sum of one layer on tube27's cells at the chooser's cutoff for tolerance 1e-6,
// no pair coefficients kept: the cost of each product of a run whose lists are too long to keep
// them (the 1,000 cells' double layer).
void BM_Tube27CellsRealSpace(benchmark::State& state) {
  const bool double_layer = state.range(0) == 1;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const ProductPoints& points = tube27_cells();
  const int n = static_cast<int>(points.x.rows());
  const EwaldChoice choice =
      choose_ewald_parameters(double_layer ? EwaldKernel::stresslet : EwaldKernel::stokeslet, 1e-6, points.box, n);
  const NeighborList list(points.box, choice.parameters.cutoff, points.x, points.x);
  const PointField f = random_field(n, 2, false);
  for (auto _ : state) {
    PointField u = double_layer ? real_space_double_layer(list, choice.parameters.xi, f, points.normals)
                                : real_space_single_layer(list, choice.parameters.xi, f);
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["pairs"] = static_cast<double>(list.n_pairs());
  state.counters["pair_ns"] = benchmark::Counter(static_cast<double>(list.n_pairs()) * 1e-9,
                                                 benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
  omp_set_num_threads(threads);
}

// Forward transform of `components` interleaved grids and the backward transform of 3, as one
// SPME product runs them, on a grid of `size` in a box of the same proportions; the first
// (planning) call is outside the timed loop.
void grid_transform(benchmark::State& state, const std::array<int, 3>& size, int components, bool measure) {
  const PeriodicBox box(Eigen::Vector3d(size[0], size[1], size[2]) / size[0]);
  const EwaldParameters p{10.0, 0.5, size, 8};
  {
    // Each case plans from scratch: no wisdom from the repetitions before it.
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_forget_wisdom();
  }
  const SpmeGrid grid(box, p, measure ? FftPlanning::measure : FftPlanning::estimate);
  // One array per 3 components, transformed in place (SpmePlan's products).
  const int arrays = components / 3;
  std::vector<FftwBuffer<fftw_complex>> data;
  for (int a = 0; a < arrays; ++a) data.emplace_back(grid.buffer_size(3));
  std::mt19937 gen(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto fill = [&] {
    for (auto& d : data)
      for (std::size_t i = 0; i < 2 * grid.buffer_size(3); ++i) SpmeGrid::real_part(d.data())[i] = u(gen);
  };
  const auto transforms = [&] {
    for (auto& d : data) grid.forward(d.data());
    grid.backward(data[0].data());
  };
  fill();
  const auto start = std::chrono::steady_clock::now();
  transforms();
  state.counters["plan_ms"] = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (auto _ : state) {
    state.PauseTiming();
    fill();
    state.ResumeTiming();
    transforms();
    benchmark::DoNotOptimize(data[0].data());
  }
}

// K x K x 2K grids: tube27's sizes.
void BM_GridTransform(benchmark::State& state) {
  const int K = static_cast<int>(state.range(0));
  grid_transform(state, {K, K, 2 * K}, static_cast<int>(state.range(1)), state.range(2) != 0);
}

// The 162 x 162 x 1600 grid of the 1,000 cells' double layer (data/cases/tube_1000_cells.toml),
// measured plans: their planning (plan_ms) is what the run pays once.
void BM_GridTransformThousandCells(benchmark::State& state) { grid_transform(state, {162, 162, 1600}, 3, true); }

void small_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {10000, 100000})
    for (int threads : {1, 2}) b->Args({n, threads});
  b->Repetitions(3)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
}
void million(benchmark::internal::Benchmark* b) {
  b->Args({1000000, 1})
      ->Args({1000000, 2})
      ->Iterations(2)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

// The neighbour list of tube27's cells: 13,824 points (random, uniform) in its 6.6 x 6.6 x
// 13.33 box, cutoffs of the single (0.891) and double layer (1.654) at tolerance 1e-6.
void BM_NeighborList(benchmark::State& state) {
  const Eigen::Vector3d side(6.6, 6.6, 13.33);
  const PeriodicBox box(side);
  const PointField x = (random_field(13824, 7, true).array().rowwise() * side.transpose().array()).matrix();
  const double cutoff = state.range(0) / 1000.0;
  std::int64_t pairs = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const NeighborList list(box, cutoff, x, x);
    pairs = list.n_pairs();
    bytes = list.memory_bytes();
  }
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["bytes_per_pair"] = static_cast<double>(bytes) / static_cast<double>(pairs);
}

}  // namespace

BENCHMARK(BM_NeighborList)
    ->Arg(891)
    ->Arg(1654)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BM_SingleLayer)->Apply(small_sizes);
BENCHMARK(BM_DoubleLayer)->Apply(small_sizes);
BENCHMARK(BM_Tube27CellsSingleLayer)->Arg(1)->Arg(2)->Repetitions(3)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Tube27CellsDoubleLayer)->Arg(1)->Arg(2)->Repetitions(3)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Tube27CellsRealSpace)->ArgsProduct({{0, 1}, {1, 2}})->Repetitions(3)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SingleLayerMillion)->Apply(million);
BENCHMARK(BM_DoubleLayerMillion)->Apply(million);

BENCHMARK(BM_GridTransform)
    ->ArgsProduct({{70, 84}, {3, 6}, {0, 1}})
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_GridTransformThousandCells)->Iterations(2)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
