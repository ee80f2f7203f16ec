// The halo of a rank's cells (operators/cell_halo.h) on spheres placed by hand: which spheres
// come within the reach of the owned ones across the periodic box, and which reach a slab of
// grid planes through their B-spline stencils (planes floor(u) - p + 1 .. floor(u) of a node at
// grid coordinate u, spme/spme_stencils.cpp). That the halo holds every cell a rank's parts of
// the layer products reach is tested on the products themselves (test_distributed_layers.cpp).
// The reach's margin for nearly-singular targets rests on the surface between the nodes lying
// within the mesh size h of the nodes' sphere, checked on the continuous surface here.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "geometry/surface/cell_grids.h"
#include "geometry/surface/reference_shapes.h"
#include "geometry/surface/sh_surface.h"
#include "libsolver/operators/cell_halo.h"

using namespace rbcflow;

namespace {

CellSphere at_z(double z, double radius) { return {Eigen::Vector3d(1.0, 1.0, z), radius}; }

}  // namespace

TEST(CellHalo, BoundingSphereHoldsEveryNode) {
  Eigen::MatrixXd nodes(4, 3);
  nodes << 0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0, 2;
  const CellSphere s = bounding_sphere(nodes);
  EXPECT_NEAR((s.center - Eigen::Vector3d(0.5, 0.5, 0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(s.radius, std::sqrt(1.5 * 1.5 + 0.25 + 0.25), 1e-15);  // (2, 0, 0) from the mean
  EXPECT_THROW(bounding_sphere(Eigen::MatrixXd(0, 3)), std::invalid_argument);
}

// A cell's nearly-singular targets are those within its near distance of the continuous
// surface (near_targets.cpp), whose points between the nodes can lie beyond the nodes' bounding
// sphere: CellLayers' reach adds the mesh size h = sqrt(A) / N (singular_quadrature.h) to the
// near distance. The surface sampled on a grid of order 64 (the coefficients zero-padded) lies
// within h of the sphere, and beyond the sphere itself (the margin is needed) for red cells and
// an ellipsoid tilted so that their rims fall between the nodes of N = 8, 12 and 16.
TEST(CellHalo, SurfaceWithinTheNodesSphereGrownByTheMeshSize) {
  const auto fine = CellGrids::make(64, 64);
  const Eigen::Matrix3d tilt =
      (Eigen::AngleAxisd(0.37, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.81, Eigen::Vector3d::UnitY())).matrix();
  for (const int N : {8, 12, 16}) {
    const auto grids = CellGrids::make(N, N);
    SHSurface red = make_biconcave(N), ellipsoid = make_ellipsoid(N, Eigen::Vector3d(1.4, 1.0, 0.5));
    for (SHSurface* s : {&red, &ellipsoid}) s->rotate(tilt);
    for (const SHSurface* s : {&red, &ellipsoid}) {
      const CellSphere sphere = bounding_sphere(grids->n_grid->synthesize(s->coeffs()));
      const Eigen::MatrixXd surface = fine->n_grid->synthesize(s->coeffs().resampled(64));
      const double farthest = (surface.rowwise() - sphere.center.transpose()).rowwise().norm().maxCoeff();
      const double h = std::sqrt(surface_area(s->geometry(*grids->n_grid))) / N;
      std::printf("N = %d: surface %.2e beyond the nodes' sphere (radius %.3f), h = %.3f\n", N,
                  farthest - sphere.radius, sphere.radius, h);
      EXPECT_GT(farthest, sphere.radius);
      EXPECT_LT(farthest, sphere.radius + h);
    }
  }
}

TEST(CellHalo, SpheresWithinReachAcrossThePeriodicBox) {
  const PeriodicBox box(Eigen::Vector3d(2.0, 2.0, 10.0));
  // Owned: cell 0 at z = 1. Cell 1 at z = 3 touches the reach (2 = 0.5 + 0.5 + 1), cell 2 at
  // z = 5 is beyond it, cell 3 at z = 9.5 is 1.5 away through the periodic end.
  const std::vector<CellSphere> spheres{at_z(1.0, 0.5), at_z(3.0, 0.5), at_z(5.0, 0.5), at_z(9.5, 0.5)};
  EXPECT_EQ(cell_halo(spheres, {0, 1}, box, 1.0, {}), (std::vector<int>{1, 2, 3}));  // no slabs: every cell
  const SlabPlanes far{2, 10, 6, 1, 2};  // plane 6 only, order 2: nothing but cell 2 comes near it
  EXPECT_EQ(cell_halo(spheres, {0, 1}, box, 1.0, {far}), (std::vector<int>{1, 2, 3}));
  const SlabPlanes none{2, 10, 0, 0, 2};  // a rank without planes
  EXPECT_EQ(cell_halo(spheres, {0, 1}, box, 1.0, {none}), (std::vector<int>{1, 3}));
  EXPECT_EQ(cell_halo(spheres, {0, 1}, box, 0.9, {none}), (std::vector<int>{3}));
  EXPECT_EQ(cell_halo(spheres, {0, 1}, std::nullopt, 0.0, {none}), (std::vector<int>{1, 2, 3}));  // free space
  // Cells 1 and 2 owned: cell 0 is 2 from cell 1, cell 3 3.5 from both, beyond 0.5 + 0.5 + 0.5.
  EXPECT_EQ(cell_halo(spheres, {1, 3}, box, 0.5, {none}), (std::vector<int>{}));
  EXPECT_THROW(cell_halo(spheres, {2, 5}, box, 1.0, {}), std::invalid_argument);
}

TEST(CellHalo, StencilsReachingASlab) {
  const PeriodicBox box(Eigen::Vector3d(2.0, 2.0, 10.0));
  const SlabPlanes slab{2, 10, 5, 1, 4};  // plane 5 of 10 (grid spacing 1), order 4
  // A node at u = 8.3 spreads to planes 5 .. 8; at u = 4.8 to 1 .. 4, at 5.2 to 2 .. 5.
  EXPECT_TRUE(reaches_slab(at_z(8.3, 0.0), slab, box));
  EXPECT_TRUE(reaches_slab(at_z(5.0, 0.2), slab, box));
  EXPECT_TRUE(reaches_slab(at_z(18.3, 0.0), slab, box));  // an image of u = 8.3
  // u in [1.8, 2.2]: planes -2 .. 2 (8, 9, 0, 1, 2), one more each side: still not plane 5.
  EXPECT_FALSE(reaches_slab(at_z(2.0, 0.2), slab, box));
  EXPECT_FALSE(reaches_slab(at_z(-8.0, 0.2), slab, box));  // its image
  // Planes 6 .. 9 and one each side: 5 .. 10, the bound's margin of one plane.
  EXPECT_TRUE(reaches_slab(at_z(9.5, 0.2), slab, box));
  EXPECT_TRUE(reaches_slab(at_z(2.0, 6.0), slab, box));  // a sphere longer than the box reaches every plane
}
