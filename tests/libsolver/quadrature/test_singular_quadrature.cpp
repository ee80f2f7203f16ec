// Validation of the singular and nearly-singular quadrature (section 5.4, docs/references.md
// sections 1 and 3). The full convergence table of Fig. 3 is in the slow test next to this.
#include "libsolver/quadrature/singular_quadrature.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <initializer_list>
#include <numbers>
#include <utility>
#include <vector>

#include "geometry/surface/surface_projection.h"
#include "libsolver/spme/ewald_parameters.h"
#include "libsolver/spme/ewald_plan.h"
#include "libsolver/spme/real_space_sum.h"
#include "quadrature_test_support.h"

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;
}

TEST(SingularQuadrature, Figure3IdentitiesConvergeAtLowOrders) {
  // Fast version of Fig. 3 (N = 8 .. 16): errors fall at better than third order.
  std::printf("   N    single layer (38)   double layer (39)\n");
  double prev_s = 0, prev_d = 0;
  for (int N : {8, 16}) {
    const auto e = quadrature_test::section8_identity_errors(
        make_squeezed_ellipsoid(N, squeezed_ellipsoid_default_rotation()), N, quadrature_test::accurate_options());
    std::printf("  %2d    %.3e           %.3e\n", N, e.single, e.double_);
    if (prev_s > 0) {
      EXPECT_GT(prev_s / e.single, 8.0);  // 2^3
      EXPECT_GT(prev_d / e.double_, 8.0);
    }
    prev_s = e.single;
    prev_d = e.double_;
  }
}

// The fast Fig. 3 again with the Ewald sums of a periodic box of side 6 (Ewald tolerance
// 1e-10): the same third-order convergence, and errors within 10% of the free-space ones
// (the identities hold in the periodic setting too; what changes is only how the regular
// rule integrates the smooth SPME part, measured at 0.005-4% of the error).
TEST(SingularQuadrature, Figure3IdentitiesWithEwaldSums) {
  const PeriodicBox box(Eigen::Vector3d::Constant(6.0));
  std::printf("   N    single layer (38)   double layer (39)   (Ewald, box 6)\n");
  double prev_s = 0, prev_d = 0;
  for (int N : {8, 16}) {
    SHSurface s = make_squeezed_ellipsoid(N, squeezed_ellipsoid_default_rotation());
    s.translate(Eigen::Vector3d(2.9, 3.1, 3.0));
    const auto o = quadrature_test::accurate_options();
    const auto e = quadrature_test::section8_identity_errors_periodic(s, N, o, box, 1e-10);
    const auto free = quadrature_test::section8_identity_errors(s, N, o);
    std::printf("  %2d    %.3e           %.3e        (free space %.3e, %.3e)\n", N, e.single, e.double_,
                free.single, free.double_);
    EXPECT_NEAR(e.single / free.single, 1.0, 0.1);
    EXPECT_NEAR(e.double_ / free.double_, 1.0, 0.1);
    if (prev_s > 0) {
      EXPECT_GT(prev_s / e.single, 8.0);  // 2^3
      EXPECT_GT(prev_d / e.double_, 8.0);
    }
    prev_s = e.single;
    prev_d = e.double_;
  }
}

TEST(SingularQuadrature, NearlySingularTargetsOffRedCellAndSqueezedEllipsoid) {
  // Targets at distance d along the normal, outside and inside (inside only where the shape
  // is thicker than 2 d: near the red cell's rim, on the ellipsoid's bulbs). Single layer of n:
  // 0; double layer of a constant U: 0 outside, -8 pi U inside. Errors relative to 8 pi.
  const int N = 16;
  const Eigen::Matrix3d R = squeezed_ellipsoid_default_rotation();
  struct Shape {
    SHSurface s;
    std::vector<std::pair<double, double>> params;
  };
  std::vector<Shape> shapes(2);
  shapes[0].s = make_biconcave(N);
  shapes[0].params = {{1.3, 0.3}, {1.57, 2.0}, {1.85, 4.4}};
  shapes[1].s = make_squeezed_ellipsoid(N, R);
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0.6, 0.2, 0.77), Eigen::Vector3d(-0.5, 0.6, -0.62), Eigen::Vector3d(0.2, -0.9, 0.38)}) {
    const Eigen::Vector3d u = R.transpose() * v.normalized();
    shapes[1].params.emplace_back(std::acos(u.z()), std::atan2(u.y(), u.x()));
  }
  for (const Shape& shape : shapes) {
    auto cell = std::make_shared<const CellQuadratureGeometry>(shape.s.coeffs(), CellGrids::make(N, N), quadrature_test::accurate_options());
    const SourceNodes& nodes = cell->nodes();
    const SHCoeffs n_coeffs = quadrature_test::normal_coeffs(shape.s.coeffs(), 2 * N);
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(nodes.size(), 3);
    U.col(0).setOnes();
    std::printf("  near distance sqrt(h) = %.3f\n   d      single/8pi  (regular)    double/8pi  (regular)\n", cell->near_distance());
    for (double d : {0.5, 0.2, 0.1, 0.05, 0.02, 0.01}) {
      double worst[2] = {0, 0}, regular[2] = {0, 0};
      for (double side : {1.0, -1.0}) {
        if (side < 0 && d > 0.2) continue;
        for (auto [t, p] : shape.params) {
          const Eigen::Vector3d xs = sh_evaluate(shape.s.coeffs(), t, p).transpose();
          const Eigen::Vector3d a1 = sh_evaluate(shape.s.coeffs(), t, p, 1, 0).transpose();
          const Eigen::Vector3d a2 = sh_evaluate(shape.s.coeffs(), t, p, 0, 1).transpose();
          const Eigen::Vector3d x0 = xs + side * d * a1.cross(a2).normalized();
          const SurfaceProjection proj = project_onto_surface(shape.s.coeffs(), x0, t, p);
          QuadratureTarget target;
          target.x = x0;
          target.theta = proj.theta;
          target.phi = proj.phi;
          target.distance = proj.distance;
          for (int layer = 0; layer < 2; ++layer) {
            const LayerKernel k{layer == 0 ? Layer::single : Layer::double_, 0.0};
            const Eigen::MatrixXd density = layer == 0 ? Eigen::MatrixXd(nodes.normal) : U;
            const Eigen::Vector3d reg = regular_layer_sum(nodes, density, k, x0.transpose()).row(0).transpose();
            Eigen::Vector3d full = reg;
            if (d < cell->near_distance()) {
              const LayerCorrection c(cell, k, {target});
              full += (layer == 0 ? c.apply(density, n_coeffs) : c.apply(density)).row(0).transpose();
            }
            const Eigen::Vector3d expected = (layer == 1 && side < 0) ? Eigen::Vector3d(-8 * pi, 0, 0) : Eigen::Vector3d::Zero();
            worst[layer] = std::max(worst[layer], (full - expected).norm() / (8 * pi));
            regular[layer] = std::max(regular[layer], (reg - expected).norm() / (8 * pi));
          }
        }
      }
      std::printf("  %.2f   %.2e   (%.1e)    %.2e   (%.1e)\n", d, worst[0], regular[0], worst[1], regular[1]);
      EXPECT_LT(worst[0], 1e-4) << "d = " << d;
      EXPECT_LT(worst[1], 1e-4) << "d = " << d;
      if (d == 0.01) {
        EXPECT_GT(regular[0], 1e-2) << "the regular rule alone should fail this close";
        EXPECT_GT(regular[1], 1e-2);
      }
    }
  }
}

TEST(SingularQuadrature, TranslatingSphereInFreeSpace) {
  // A rigid sphere (a = 1) translating with U exerts the uniform traction 3 U / (2 a) on the
  // fluid; the single layer (1 / 8 pi) integral G f dS gives U at every node.
  const int N = 16;
  auto cell = std::make_shared<const CellQuadratureGeometry>(make_sphere(N).coeffs(), CellGrids::make(N, N),
                                                            quadrature_test::accurate_options());
  const Eigen::Vector3d U(0.3, -1.0, 0.5);
  const Eigen::MatrixXd f = (1.5 * U).transpose().replicate(cell->nodes().size(), 1);
  const Eigen::MatrixXd u = free_space_layer_on_nodes(cell, Layer::single, f) / (8 * pi);
  const double err = (u.rowwise() - U.transpose()).cwiseAbs().maxCoeff() / U.norm();
  std::printf("  max relative velocity error at N = %d: %.2e\n", N, err);
  EXPECT_LT(err, 1e-6);
}

TEST(SingularQuadrature, SphereInPeriodicArrayMatchesHasimoto) {
  // Uniform traction on a sphere (a = 1) in a cubic box of side L: the mean surface velocity
  // gives K = F / (6 pi U) = 1.53022 (L = 8) and 1.38805 (L = 10) (REFERENCES section 3).
  // Ewald: SPME + real-space regular rule + singular corrections of the real-space kernel.
  const int N = 16;
  const SHSurface sphere = make_sphere(N);
  for (auto [L, K_ref] : {std::pair{8.0, 1.53022}, {10.0, 1.38805}}) {
    SHSurface s = sphere;
    s.translate(Eigen::Vector3d::Constant(L / 2));
    auto cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), CellGrids::make(N, N));
    const SourceNodes& nodes = cell->nodes();
    const PeriodicBox box(Eigen::Vector3d::Constant(L));
    const EwaldChoice choice = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-9, box, nodes.size());
    auto grid = std::make_shared<const SpmeGrid>(box, choice.parameters, FftPlanning::estimate);
    EwaldPlan plan(grid, nodes.x);
    const Eigen::Vector3d F(0.0, 0.0, 1.0);  // total force on the fluid
    const Eigen::MatrixXd f = (F / (4 * pi)).transpose().replicate(nodes.size(), 1);
    const PointField weighted = f.array().colwise() * nodes.weight.array();
    const LayerCorrection correction(cell, LayerKernel{Layer::single, choice.parameters.xi}, cell->node_targets());
    const Eigen::MatrixXd u = (plan.single_layer(weighted) + correction.apply(f)) / (8 * pi);
    const Eigen::Vector3d mean = (u.array().colwise() * nodes.weight.array()).colwise().sum() / nodes.weight.sum();
    const double K = F.norm() / (6 * pi * mean.z());
    std::printf("  L = %4.1f: K = %.6f (reference %.5f), transverse %.1e\n", L, K, K_ref, mean.head<2>().norm());
    EXPECT_NEAR(K, K_ref, 1e-4);
  }
}

namespace {

// Targets `offset` off the surface along its normal at the parameters (theta, phi) given, with
// their projections onto it.
std::vector<QuadratureTarget> off_surface_targets(const SHSurface& s, double offset,
                                                  std::initializer_list<std::pair<double, double>> at) {
  std::vector<QuadratureTarget> near;
  for (auto [t, p] : at) {
    const Eigen::Vector3d xs = sh_evaluate(s.coeffs(), t, p).transpose();
    const Eigen::Vector3d a1 = sh_evaluate(s.coeffs(), t, p, 1, 0).transpose();
    const Eigen::Vector3d a2 = sh_evaluate(s.coeffs(), t, p, 0, 1).transpose();
    const Eigen::Vector3d x0 = xs + offset * a1.cross(a2).normalized();
    const SurfaceProjection proj = project_onto_surface(s.coeffs(), x0, t, p);
    EXPECT_TRUE(proj.converged);
    near.push_back({x0, proj.theta, proj.phi, proj.distance, -1});
  }
  return near;
}

// The chooser's single- and double-layer parameters for the cell's nodes in `box`.
std::array<EwaldParameters, 2> chosen(const CellQuadratureGeometry& cell, const PeriodicBox& box, double tolerance) {
  const int n = cell.nodes().size();
  return {choose_ewald_parameters(EwaldKernel::stokeslet, tolerance, box, n).parameters,
          choose_ewald_parameters(EwaldKernel::stresslet, tolerance, box, n).parameters};
}

// Single and double layers of `cell` in `box` at its nodes and at `near` points (targets with
// their projections), SPME + real-space sums + corrections at the Ewald tolerance given. fold:
// the corrections leave their patch nodes within the real-space cutoff to the real-space sums
// (PairShares); `folded` counts those (target, node) entries. reach: they remove no share of
// the nodes beyond the cutoff (as CellLayers builds them).
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> periodic_layers(const std::shared_ptr<const CellQuadratureGeometry>& cell,
                                                            const PeriodicBox& box,
                                                            const std::vector<QuadratureTarget>& near,
                                                            const std::array<EwaldParameters, 2>& parameters,
                                                            bool fold, bool reach, std::size_t& folded) {
  const SourceNodes& nodes = cell->nodes();
  const int n = nodes.size(), k = static_cast<int>(near.size());
  PointField targets(n + k, 3);
  targets.topRows(n) = nodes.x;
  for (int i = 0; i < k; ++i) targets.row(n + i) = near[i].x.transpose();
  std::shared_ptr<const SpmeGrid> grid[2];
  std::array<NodeShares, 2> node_shares{};
  for (int l = 0; l < 2; ++l) {
    grid[l] = std::make_shared<const SpmeGrid>(box, parameters[l], FftPlanning::estimate);
    if (fold) node_shares[l].fold = pair_share_radius(box, parameters[l].cutoff);
    if (reach) node_shares[l].reach = parameters[l].cutoff;
  }
  const double xi_s = grid[0]->parameters().xi, xi_d = grid[1]->parameters().xi;
  auto self = LayerCorrection::single_and_double(cell, xi_s, xi_d, cell->node_targets(), node_shares);
  auto close = LayerCorrection::single_and_double(cell, xi_s, xi_d, near, node_shares);
  folded = 0;
  auto shares = [&](const LayerCorrection& s, const LayerCorrection& c) {
    // A segment per target pointing to the corrections' folded nodes, as CellLayers leaves them.
    PairShares p;
    p.offsets.push_back(0);
    for (int t = 0; t < n + k; ++t) {
      const std::span<const PatchNode> patch = t < n ? s.folded(t) : c.folded(t - n);
      if (!patch.empty()) p.segments.push_back({patch.data(), static_cast<std::int32_t>(patch.size()), 0});
      p.offsets.push_back(static_cast<std::int64_t>(p.segments.size()));
      folded += patch.size();
    }
    return p;
  };
  EwaldPlan single(grid[0], nodes.x, targets, shares(*self.first, *close.first));
  EwaldPlan dbl(grid[1], nodes.x, targets, shares(*self.second, *close.second));
  // A smooth force density (the normal's single layer cancels over the closed surface) and the
  // position as the double layer's.
  Eigen::MatrixXd f(n, 3);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d x = nodes.x.row(i);
    f.row(i) << std::sin(x.y()) + 0.3, x.x() * x.z(), std::cos(x.x() + 0.5 * x.y());
  }
  const Eigen::MatrixXd u = nodes.x;
  Eigen::MatrixXd sl = single.single_layer(f.array().colwise() * nodes.weight.array());
  Eigen::MatrixXd dl = dbl.double_layer(u.array().colwise() * nodes.weight.array(), nodes.normal);
  sl.topRows(n) += self.first->apply(f);
  sl.bottomRows(k) += close.first->apply(f);
  dl.topRows(n) += self.second->apply(u);
  dl.bottomRows(k) += close.second->apply(u);
  return {sl, dl};
}

}  // namespace

// The regular rule's share of each patch (eta K w at the nodes inside it) taken out of the
// real-space Ewald sums (pairs weighted 1 - eta) instead of by the corrections: the same layers
// up to the order of summation (1e-12 of their norm), at the nodes and at nearly-singular
// targets 0.1 off the surface. With the runs' single-precision tables the double layer's node
// entries are rounded where its folded pairs are not: that layer then agrees to the solver's
// tolerance (1e-6; float rounding predicts ~1e-8, as the entries hardly cancel against the
// real-space sum). The single layer's would (rounded, it moved by 1.5e-6): they stay double.
// In the box of side 1.6 across the cell, half the side (0.8) leaves part of each patch beyond
// the nearest-image radius, in the corrections.
TEST(LayerCorrection, FoldedPatchNodesGiveTheSameLayers) {
  const int N = 12;
  for (const bool compact : {false, true}) {
    QuadratureOptions options;
    options.compact_tables = compact;
    const double double_layer_tolerance = compact ? 1e-6 : 1e-12;
    std::size_t folded_in[2] = {0, 0};
    int b = 0;
    for (const Eigen::Vector3d& side : {Eigen::Vector3d(6.0, 6.0, 6.0), Eigen::Vector3d(3.2, 3.2, 1.6)}) {
      const PeriodicBox box(side);
      SHSurface s = make_biconcave(N);
      s.translate(0.5 * side);
      auto cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), CellGrids::make(N, N), options);
      const std::vector<QuadratureTarget> near = off_surface_targets(s, 0.1, {{1.3, 0.3}, {1.57, 2.0}, {0.4, 4.4}});
      std::size_t none = 0;
      const auto [sl, dl] = periodic_layers(cell, box, near, chosen(*cell, box, 1e-8), false, true, none);
      const auto [sl_folded, dl_folded] = periodic_layers(cell, box, near, chosen(*cell, box, 1e-8), true, true, folded_in[b]);
      EXPECT_EQ(none, 0u);
      std::printf("  %s tables, box %.1f x %.1f x %.1f: %zu folded patch nodes, differences %.1e (single), %.1e (double)\n",
                  compact ? "compact" : "double", side.x(), side.y(), side.z(), folded_in[b],
                  (sl_folded - sl).norm() / sl.norm(), (dl_folded - dl).norm() / dl.norm());
      EXPECT_LT((sl_folded - sl).norm(), 1e-12 * sl.norm());
      EXPECT_LT((dl_folded - dl).norm(), double_layer_tolerance * dl.norm());
      ++b;
    }
    EXPECT_GT(folded_in[1], 0u);
    EXPECT_LT(folded_in[1], folded_in[0]);  // the small box keeps part of the patches in the corrections
  }
}

// The real-space sums hold no pair beyond their cutoff, so the corrections remove no share
// there (NodeShares::reach): a red cell at N = 16 in a box of side 4, the chooser's parameters
// at the runs' tolerance (1e-6: cutoffs 1.59 and 1.81, where the 1,000-cell tube's are 1.26
// and 1.53; the patches, rho_1 = pi / 2 on the parameter sphere, reach farther), against the
// same xi and grids with every patch inside a cutoff of 3.5. Removing the shares beyond the cutoff would add -eta K w of a kernel the
// truncation drops, so the layers without them are no farther from the reference than with
// them; both are within the tolerance. With the fold radius at the cutoff, the double layer
// keeps no node entries at all.
TEST(LayerCorrection, PatchNodesBeyondTheCutoffHaveNoShare) {
  const int N = 16;
  const PeriodicBox box(Eigen::Vector3d(4.0, 4.0, 4.0));
  SHSurface s = make_biconcave(N);
  s.translate(Eigen::Vector3d(2.0, 2.0, 2.0));
  auto cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), CellGrids::make(N, N));
  const std::vector<QuadratureTarget> near = off_surface_targets(s, 0.05, {{1.3, 0.3}, {1.57, 2.0}, {0.4, 4.4}, {2.9, 1.0}});
  const std::array<EwaldParameters, 2> p = chosen(*cell, box, 1e-6);
  std::array<EwaldParameters, 2> wide = p;
  for (EwaldParameters& w : wide) w.cutoff = 3.5;
  std::size_t folded = 0;
  const auto [sl_ref, dl_ref] = periodic_layers(cell, box, near, wide, true, true, folded);
  double error[2][2];  // [without, with the reach][single, double]
  for (const bool reach : {false, true}) {
    const auto [sl, dl] = periodic_layers(cell, box, near, p, true, reach, folded);
    error[reach][0] = (sl - sl_ref).norm() / sl_ref.norm();
    error[reach][1] = (dl - dl_ref).norm() / dl_ref.norm();
    std::printf("  cutoffs %.3f, %.3f, %s shares beyond them: errors %.2e (single), %.2e (double)\n", p[0].cutoff,
                p[1].cutoff, reach ? "no" : "with", error[reach][0], error[reach][1]);
  }
  for (int l = 0; l < 2; ++l) {
    EXPECT_LT(error[1][l], 1e-6);
    EXPECT_LE(error[1][l], error[0][l] * (1 + 1e-3));
  }
  std::array<NodeShares, 2> at_cutoff;
  for (int l = 0; l < 2; ++l) at_cutoff[l] = {pair_share_radius(box, p[l].cutoff), p[l].cutoff};
  std::array<NodeShares, 2> kept_beyond = at_cutoff;
  for (NodeShares& k : kept_beyond) k.reach = std::numeric_limits<double>::infinity();
  const auto node_entry_bytes = [&](const std::array<NodeShares, 2>& shares) {
    const auto both = LayerCorrection::single_and_double(cell, p[0].xi, p[1].xi, cell->node_targets(), shares);
    MemoryReport report;
    both.second->report_memory(report, "double");
    for (const MemoryReport::Item& i : report.items())
      if (i.name == "double: node entries") return i.bytes - (cell->nodes().size() + 1) * sizeof(std::int64_t);
    return std::size_t{0};
  };
  const std::size_t beyond = node_entry_bytes(kept_beyond), none = node_entry_bytes(at_cutoff);
  std::printf("  double layer's node entries: %zu bytes with the shares beyond the cutoff, %zu without\n", beyond, none);
  EXPECT_GT(beyond, 0u);
  EXPECT_EQ(none, 0u);
}

// The tables kept in single precision (QuadratureOptions::compact_tables, the default) against
// double: a red cell at N = 16 as in the runs, its self corrections and nearly-singular ones at
// targets 0.05 off the surface, free-space and Ewald real-space kernels, a smooth density. The
// difference, relative to the correction itself, must stay below the 1e-6 Ewald and GMRES
// tolerances of a run; float rounding summed over a patch predicts ~1e-7.
TEST(LayerCorrection, CompactTablesChangeTheCorrectionsBelowTheSolverTolerance) {
  const int N = 16;
  const SHSurface s = make_biconcave(N);
  QuadratureOptions full;
  full.compact_tables = false;
  const auto grids = CellGrids::make(N, 3 * N);
  const auto compact_cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), grids);
  const auto full_cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), grids, full);
  const std::vector<QuadratureTarget> near = off_surface_targets(s, 0.05, {{1.3, 0.3}, {1.57, 2.0}, {0.4, 4.4}, {2.9, 1.0}});
  const SourceNodes& nodes = compact_cell->nodes();
  Eigen::MatrixXd density(nodes.size(), 3);
  for (int i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d x = nodes.x.row(i);
    density.row(i) << std::sin(x.y()) + 0.3, x.x() * x.z(), std::cos(x.x() + 0.5 * x.y());
  }
  double worst = 0.0;
  for (const double xi : {0.0, 0.8}) {
    for (const auto& targets : {compact_cell->node_targets(), near}) {
      const auto compact = LayerCorrection::single_and_double(compact_cell, xi, xi, targets);
      const auto reference = LayerCorrection::single_and_double(full_cell, xi, xi, targets);
      for (int l = 0; l < 2; ++l) {
        const Eigen::MatrixXd a = (l == 0 ? compact.first : compact.second)->apply(density);
        const Eigen::MatrixXd b = (l == 0 ? reference.first : reference.second)->apply(density);
        const double difference = (a - b).norm() / b.norm();
        std::printf("  xi %.1f, %s targets, %s layer: relative difference %.1e\n", xi,
                    targets.size() == near.size() ? "near" : "node", l == 0 ? "single" : "double", difference);
        worst = std::max(worst, difference);
      }
    }
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(worst, 0.0);  // the compact tables are in use
}
