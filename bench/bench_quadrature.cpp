// Singular-quadrature corrections of one red cell (issue: quadrature).
//   OMP_NUM_THREADS=1 build/bin/bench_quadrature ; OMP_NUM_THREADS=2 build/bin/bench_quadrature
// Build: once per time step (geometry-dependent). Apply: every GMRES product. For scale, the
// periodic single-layer product over the same nodes (SPME + real space, tolerance 1e-6).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "geometry/surface/reference_shapes.h"
#include "geometry/surface/surface_projection.h"
#include "libsolver/quadrature/singular_quadrature.h"
#include "libsolver/spme/ewald_parameters.h"
#include "libsolver/spme/ewald_plan.h"

using namespace rbcflow;

namespace {

std::shared_ptr<const CellQuadratureGeometry> red_cell(int N) {
  SHSurface s = make_biconcave(N);
  s.translate(Eigen::Vector3d::Constant(5.0));
  return std::make_shared<const CellQuadratureGeometry>(s.coeffs(), CellGrids::make(N, N));
}

// The nodes of a second cell 0.1 above this one (its lower dimple over this cell's upper
// one) that fall within the near distance: nearly singular targets with their projections.
std::vector<QuadratureTarget> neighbour_targets(const CellQuadratureGeometry& cell) {
  const SourceNodes& nodes = cell.nodes();
  const double gap = 0.1 + (nodes.x.col(2).maxCoeff() - nodes.x.col(2).minCoeff());
  std::vector<QuadratureTarget> targets;
  const SphGrid& grid = cell.grids().n_grid->grid();
  for (int p = 0; p < nodes.size(); ++p) {
    const Eigen::Vector3d x0 = Eigen::Vector3d(nodes.x.row(p)) + Eigen::Vector3d(0, 0, gap);
    const double t = grid.theta()[p / grid.n_phi()], ph = grid.phi(p % grid.n_phi());
    const SurfaceProjection proj = project_onto_surface(cell.coeffs(), x0, t, ph);
    if (proj.distance >= cell.near_distance() || proj.signed_distance < 0) continue;
    QuadratureTarget q;
    q.x = x0;
    q.theta = proj.theta;
    q.phi = proj.phi;
    q.distance = proj.distance;
    targets.push_back(q);
  }
  return targets;
}

void BM_BuildSelfCorrection(benchmark::State& state) {
  const auto cell = red_cell(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    LayerCorrection c(cell, {Layer::single, 2.0}, cell->node_targets());
    benchmark::DoNotOptimize(&c);
  }
  state.counters["targets"] = cell->nodes().size();
}
BENCHMARK(BM_BuildSelfCorrection)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Unit(benchmark::kMillisecond);

// Both layers with their Ewald splits, as a step with viscosity ratio != 1 builds them.
void BM_BuildSelfSingleAndDouble(benchmark::State& state) {
  const auto cell = red_cell(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto both = LayerCorrection::single_and_double(cell, 2.0, 1.5, cell->node_targets());
    benchmark::DoNotOptimize(&both);
  }
  state.counters["targets"] = cell->nodes().size();
}
BENCHMARK(BM_BuildSelfSingleAndDouble)->Arg(12)->Arg(16)->Arg(24)->Unit(benchmark::kMillisecond);

void BM_BuildNeighbourCorrection(benchmark::State& state) {
  const auto cell = red_cell(static_cast<int>(state.range(0)));
  const auto targets = neighbour_targets(*cell);
  for (auto _ : state) {
    LayerCorrection c(cell, {Layer::single, 2.0}, targets);
    benchmark::DoNotOptimize(&c);
  }
  state.counters["targets"] = static_cast<double>(targets.size());
}
BENCHMARK(BM_BuildNeighbourCorrection)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Unit(benchmark::kMillisecond);

void BM_ApplySelfCorrection(benchmark::State& state) {
  const auto cell = red_cell(static_cast<int>(state.range(0)));
  const LayerCorrection c(cell, {Layer::single, 2.0}, cell->node_targets());
  const Eigen::MatrixXd f = Eigen::MatrixXd::Random(cell->nodes().size(), 3);
  for (auto _ : state) benchmark::DoNotOptimize(c.apply(f).data());
}
BENCHMARK(BM_ApplySelfCorrection)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Unit(benchmark::kMillisecond);

// Tables of single targets (one per nearly singular target): stencils kept as the points'
// places, their weights computed at each product.
void BM_ApplyNeighbourCorrection(benchmark::State& state) {
  const auto cell = red_cell(static_cast<int>(state.range(0)));
  const auto targets = neighbour_targets(*cell);
  const LayerCorrection c(cell, {Layer::single, 2.0}, targets);
  const Eigen::MatrixXd f = Eigen::MatrixXd::Random(cell->nodes().size(), 3);
  for (auto _ : state) benchmark::DoNotOptimize(c.apply(f).data());
  state.counters["targets"] = static_cast<double>(targets.size());
}
BENCHMARK(BM_ApplyNeighbourCorrection)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Unit(benchmark::kMillisecond);

void BM_PeriodicSingleLayerProduct(benchmark::State& state) {
  const auto cell = red_cell(static_cast<int>(state.range(0)));
  const PeriodicBox box(Eigen::Vector3d::Constant(10.0));
  const EwaldChoice choice = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, cell->nodes().size());
  EwaldPlan plan(std::make_shared<const SpmeGrid>(box, choice.parameters, FftPlanning::estimate), cell->nodes().x);
  const PointField f = PointField::Random(cell->nodes().size(), 3);
  for (auto _ : state) benchmark::DoNotOptimize(plan.single_layer(f).data());
}
BENCHMARK(BM_PeriodicSingleLayerProduct)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
