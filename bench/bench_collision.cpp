// Collision removal (section 11.2): unit spheres at N = 16 on an S x S x S lattice in a
// periodic box, h_s = 0.04. Arguments: S, and the lattice gap in hundredths, 0.5 (nothing
// within h_s: detection by bounding spheres only) or 0.02 (every cell within h_s of its six
// neighbours; the grid points find 54 pairs at S = 3). Counters: pairs found, detection passes.
// S = 10 at a gap of 0.5 (1,000 cells, no contact) times the search for close pairs and the
// cells' grid points alone: 171 ms with every pair of cells tested, 25 ms from bins of the
// centres (1 thread, b70eaa1 against the commit that adds the bins).
// BM_PlaceTubeCells, BM_PlaceWideTubeCells: random placement of K red cells (N = 16) at the
// tube hematocrit 0.30 in the D = 6 tube of bench_step's tubeK cases and in the D = 12 tube of
// the 1,000-cell case (sequential addition, then compression), three seeds / one.
//   build/bin/bench_collision
#include <benchmark/benchmark.h>

#include <numbers>
#include <vector>

#include "geometry/contact/cell_placement.h"
#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"
#include "libsolver/stepper/collision.h"

using namespace rbcflow;

namespace {

void BM_CollisionLattice(benchmark::State& state) {
  const int order = 16;
  const int side = static_cast<int>(state.range(0));
  const double gap = state.range(1) / 100.0, spacing = 2.0 + gap;
  const SHTransform t = SHTransform::gauss(order);
  std::vector<SHSurface> lattice;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k) {
        SHSurface s = make_sphere(order);
        s.translate(spacing * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
        lattice.push_back(std::move(s));
      }
  const Eigen::Vector3d box = Eigen::Vector3d::Constant(side * spacing);
  CollisionReport r;
  for (auto _ : state) {
    std::vector<SHSurface> cells = lattice;
    r = remove_collisions(cells, t, box, nullptr, 0.04);
    benchmark::DoNotOptimize(cells.data());
  }
  state.counters["pairs"] = r.cell_pairs;
  state.counters["passes"] = r.passes;
}
BENCHMARK(BM_CollisionLattice)->Args({3, 50})->Args({3, 2})->Args({10, 50})->Unit(benchmark::kMillisecond);

// K cells (N = 16) at H_T = 0.30 in a tube of diameter D with the wall meshed at size h; the
// period holds the K cells. Placement is random, so its cost varies with the seed.
void place_in_tube(benchmark::State& state, double diameter, double element_size) {
  const int count = static_cast<int>(state.range(0));
  const double side = diameter + 0.6;
  const double cells_per_length = 0.30 * 0.25 * std::numbers::pi * diameter * diameter / (4.0 / 3.0 * std::numbers::pi);
  const Eigen::Vector3d box(side, side, count / cells_per_length);
  const VesselMesh vessel = tube(TubeSpec{diameter, 2, box, element_size});
  const SHSurface rbc = make_biconcave(16);
  PlacementSpec spec;
  spec.box = box;
  spec.count = count;
  spec.gap = 0.05;
  spec.seed = static_cast<std::uint64_t>(state.range(1));
  int sweeps = 0;
  for (auto _ : state) {
    const Placement p = place_cells(rbc, spec, &vessel);
    benchmark::DoNotOptimize(p.cells.data());
    sweeps = p.compression_sweeps;
  }
  state.counters["sweeps"] = sweeps;
  state.counters["s_per_cell"] = benchmark::Counter(count, benchmark::Counter::kIsIterationInvariantRate |
                                                               benchmark::Counter::kInvert);
}

// bench_step's tubeK cases: the D = 6 tube of data/cases/tube_27_cells.toml, h = 0.25.
void BM_PlaceTubeCells(benchmark::State& state) { place_in_tube(state, 6.0, 0.25); }
BENCHMARK(BM_PlaceTubeCells)
    ->ArgsProduct({{8, 27, 64, 125}, {1, 2, 3}})
    ->ArgNames({"cells", "seed"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// data/cases/tube_1000_cells.toml's D = 12 tube, h = 0.4.
void BM_PlaceWideTubeCells(benchmark::State& state) { place_in_tube(state, 12.0, 0.4); }
BENCHMARK(BM_PlaceWideTubeCells)
    ->ArgsProduct({{125, 512, 1000}, {1}})
    ->ArgNames({"cells", "seed"})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
