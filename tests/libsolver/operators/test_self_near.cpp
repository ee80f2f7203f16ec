// Parts of one cell near each other (libsolver/operators/near_targets.h): the two faces at a
// red cell's dimple. The double-layer identity (39), p.v. integral T . n dS = -4 pi (an exact
// identity of the closed surface), measured at every node in free space: with the self-near
// patches, and with the singular patch alone (free_space_layer_on_nodes); and a parachute's
// folded rim, which lies inside the singular patch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/surface/parachute_fold.h"
#include "geometry/surface/reference_shapes.h"
#include "libsolver/operators/cell_layers.h"
#include "libsolver/operators/near_targets.h"
#include "libsolver/quadrature/singular_quadrature.h"

using namespace rbcflow;

namespace {

constexpr double pi = std::numbers::pi;

// Largest error of the identity over the nodes, relative to 4 pi |U|, and the node's height.
struct WorstNode {
  double error, z;
};

WorstNode worst(const Eigen::MatrixXd& dl, const Eigen::MatrixXd& U, const SourceNodes& nodes) {
  const Eigen::MatrixXd e = dl + 4 * pi * U;
  int p = 0;
  const double m = e.rowwise().norm().maxCoeff(&p);
  return {m / (4 * pi * U.row(0).norm()), nodes.x(p, 2)};
}

}  // namespace

TEST(SelfNear, DimpleFacesGetNearlySingularPatchesAndTheIdentityImproves) {
  std::printf("   N  self-near nodes  max error: singular patch only (at z)   with self-near (at z)\n");
  for (int N : {12, 16, 24}) {
    const SHSurface rbc = make_biconcave(N);
    const auto grids = CellGrids::make(N, N);
    auto cell = std::make_shared<const CellQuadratureGeometry>(rbc.coeffs(), grids);
    const NearTargets self = find_self_near_targets(*cell);
    const SourceNodes& nodes = cell->nodes();
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(nodes.size(), 3);
    U.col(0).setConstant(1.0);
    U.col(2).setConstant(0.5);
    const WorstNode before = worst(free_space_layer_on_nodes(cell, Layer::double_, U), U, nodes);
    CellLayers layers({rbc.coeffs()}, grids, LayerDomain{});
    const WorstNode after = worst(layers.double_layer(U), U, nodes);
    std::printf("  %2d  %4zu            %.3e (%+.3f)                    %.3e (%+.3f)\n", N, self.rows.size(),
                before.error, before.z, after.error, after.z);
    EXPECT_GT(self.rows.size(), 0u);
    for (std::size_t k = 0; k < self.rows.size(); ++k) {
      const double r = nodes.x.row(self.rows[k]).head<2>().norm();
      EXPECT_LT(r, 0.8) << "only the dimple's faces are within the near distance of each other";
      EXPECT_LT(self.targets[k].distance, cell->near_distance());
    }
    // Measured: 3.4e-2 -> 2.6e-3, 1.4e-2 -> 2.0e-4, 1.9e-3 -> 1.3e-4 at N = 12, 16, 24 (13-70x).
    EXPECT_LT(after.error, 0.2 * before.error);
    if (N >= 16) {
      EXPECT_LT(after.error, 1e-3);
    }
  }
}

// A sphere has no part near another: no self-near targets, and the identity is the same.
TEST(SelfNear, SphereHasNone) {
  const auto grids = CellGrids::make(16, 16);
  auto cell = std::make_shared<const CellQuadratureGeometry>(make_sphere(16).coeffs(), grids);
  EXPECT_TRUE(find_self_near_targets(*cell).rows.empty());
}

// A fold whose two sides are close on the parameter sphere too (the rim of a parachute,
// geometry/surface/parachute_fold.h, radius 0.78 as in the D = 1.75 quick tube) lies inside each node's
// own singular patch: there the radial patch points decide. Measured at N = 16, largest error
// of the identity: 6.5e-2 with the default 12 radial points, 1.6e-2 with 24 (docs/fahraeus.md).
TEST(SelfNear, ParachuteRimNeedsMoreRadialPatchPoints) {
  const int N = 16;
  const SHSurface parachute = fold_into_parachute(make_biconcave(N), 0.78).surface;
  const auto grids = CellGrids::make(N, N);
  double errors[2];
  for (int k = 0; k < 2; ++k) {
    QuadratureOptions o;
    if (k == 1) o.radial_points = 24, o.angular_points = 48;
    auto cell = std::make_shared<const CellQuadratureGeometry>(parachute.coeffs(), grids, o);
    const SourceNodes& nodes = cell->nodes();
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(nodes.size(), 3);
    U.col(0).setConstant(1.0);
    U.col(1).setConstant(0.5);
    const WorstNode w = worst(free_space_layer_on_nodes(cell, Layer::double_, U), U, nodes);
    errors[k] = w.error;
    std::printf("radial points %d: largest error %.3e at z = %+.3f (the rim is at the rear, z < -0.9)\n",
                k ? 24 : default_radial_points(N), w.error, w.z);
    EXPECT_LT(w.z, -0.9);  // at the folded rim, not the nose
  }
  EXPECT_GT(errors[0], 2e-2);              // under-resolved at the default
  EXPECT_LT(errors[1], 0.5 * errors[0]);   // more radial points resolve it
}
