#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "geometry/vessel/mesh_check.h"
#include "tests/geometry/vessel/fillet_folds.h"
#include "geometry/vessel/mesh_orientation.h"
#include "geometry/vessel/vessel.h"

using namespace rbcflow;

namespace {

// data/cases/bifurcation.toml: parent D = 3, daughters 2.4 and 2.2 at 60 degrees, split at
// z = 5 in a 12 x 6 x 16 box; a coarser element size for speed.
BifurcationSpec example(double h = 0.3) {
  BifurcationSpec s;
  s.tube.diameter = 3.0;
  s.tube.axis = 2;
  s.tube.box = Eigen::Vector3d(12.0, 6.0, 16.0);
  s.tube.element_size = h;
  s.daughter_diameters = {2.4, 2.2};
  s.angle_deg = 60.0;
  s.centre = 5.0;
  return s;
}

double lateral_distance(const Eigen::Vector3d& x, const Eigen::Vector2d& axis) {
  return (x.head<2>() - axis).norm();
}

void expect_invalid(const BifurcationSpec& s, const std::string& words) {
  try {
    bifurcation_layout(s);
    FAIL() << "no error, expected one about " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

}  // namespace

// A closed, consistently oriented wall (check_mesh passed inside the builder) with normals into
// the lumen; parent nodes on the parent's cylinder and daughter nodes on the daughters' in the
// parallel part of the loop, both exact surfaces of the CAD model (OCC tolerance 1e-7).
TEST(Bifurcation, ExampleCaseWallLiesOnItsSurfaces) {
  const BifurcationSpec s = example();
  const BifurcationLayout l = bifurcation_layout(s);
  const VesselMesh wall = bifurcation(s);
  const MeshQuality q = check_mesh(wall);
  std::printf("bifurcation h = %.2f: %d nodes, %d triangles, min angle %.1f deg, area %.2f, lumen volume %.2f\n",
              s.tube.element_size, wall.surface.num_points(), wall.surface.num_triangles(), q.min_angle_deg, q.area,
              -0.5 * lumen_flux(wall));
  EXPECT_EQ(wall.period, Eigen::Vector3d(0, 0, 16.0));
  EXPECT_LT(lumen_flux(wall), 0.0);  // normals into the lumen
  EXPECT_GT(q.min_angle_deg, 10.0);
  EXPECT_LT(q.max_edge, 2.0 * s.tube.element_size);

  const double R = 1.5, r0 = 1.2, r1 = 1.1, split = 5.0, merge = 13.0;
  const Eigen::Vector2d axis(6.0, 3.0);
  const double loop_middle = 0.5 * (split + merge);
  int on_parent = 0, on_daughters = 0;
  double widest = 0;
  for (int i = 0; i < wall.surface.num_points(); ++i) {
    const Eigen::Vector3d x = wall.surface.points.row(i);
    ASSERT_GE(x[2], 0.0);
    ASSERT_LT(x[2], 16.0);
    widest = std::max(widest, std::abs(x[0] - axis[0]));
    // Away from the junction spheres (radius R around the split and merge points).
    if (x[2] < split - R || x[2] > merge + R) {
      EXPECT_NEAR(lateral_distance(x, axis), R, 1e-6 * R) << x.transpose();
      ++on_parent;
    }
    if (std::abs(x[2] - loop_middle) < 0.5 * l.parallel[0]) {
      const bool first = x[0] > axis[0];
      const Eigen::Vector2d centre(axis[0] + (first ? 1 : -1) * l.offset, axis[1]);
      EXPECT_NEAR(lateral_distance(x, centre), first ? r0 : r1, 1e-6 * R) << x.transpose();
      ++on_daughters;
    }
  }
  EXPECT_GT(on_parent, 100);
  EXPECT_GT(on_daughters, 20);
  // The widest point is the first (larger) daughter's outer wall.
  EXPECT_NEAR(widest, l.offset + r0, 0.02);
}

// The split at `centre` is only a shift along the axis: the same mesh, wrapped through the box.
TEST(Bifurcation, CentreShiftsTheWallThroughTheBox) {
  BifurcationSpec a = example(0.4), b = example(0.4);
  b.centre = 8.0;  // the default: half the box; the loop crosses the box face
  const VesselMesh wa = bifurcation(a), wb = bifurcation(b);
  ASSERT_EQ(wa.surface.num_triangles(), wb.surface.num_triangles());
  ASSERT_EQ(wa.surface.num_points(), wb.surface.num_points());
  EXPECT_NEAR(wa.surface.points.col(2).maxCoeff(), wb.surface.points.col(2).maxCoeff(), 0.5);
  EXPECT_NEAR(lumen_flux(wa), lumen_flux(wb), 1e-9 * std::abs(lumen_flux(wa)));
  const MeshQuality qa = check_mesh(wa), qb = check_mesh(wb);
  EXPECT_NEAR(qa.area, qb.area, 1e-9 * qa.area);
}

// fillet_radius rounds the creases where parent and daughters meet. Sharp, the divider's ridge
// folds the wall by ~90 degrees between two triangles; rounded with r = 0.5, the steepest fold
// is the fillet's own curvature resolved by edges of ~h: h / r = 0.6 rad (34 degrees), up to 45
// for edges of 1.3 h. Away from the junctions the wall is the same: the daughters' surfaces in
// the parallel part of the loop.
TEST(Bifurcation, FilletRoundsTheJunctionCreases) {
  BifurcationSpec s = example();
  s.fillet_radius = 0.5;
  const FilletFolds f = sharp_and_rounded(example(), s.fillet_radius, [](const BifurcationSpec& b) { return bifurcation(b); });
  const VesselMesh& rounded = f.rounded;
  EXPECT_GT(f.sharp_fold_deg, 60.0);
  EXPECT_LT(f.quality.max_fold_deg, 45.0);
  EXPECT_LT(lumen_flux(rounded), 0.0);  // normals into the lumen
  const BifurcationLayout l = bifurcation_layout(s);
  const Eigen::Vector2d axis(6.0, 3.0);
  int on_parent = 0, on_daughters = 0;
  for (int i = 0; i < rounded.surface.num_points(); ++i) {
    const Eigen::Vector3d x = rounded.surface.points.row(i);
    if (x[2] < 5.0 - 1.5 || x[2] > 13.0 + 1.5) {  // the parent, up to the box faces
      EXPECT_NEAR(lateral_distance(x, axis), 1.5, 1e-6) << x.transpose();
      ++on_parent;
    }
    if (std::abs(x[2] - 9.0) >= 0.5 * l.parallel[0]) continue;
    const bool first = x[0] > axis[0];
    const Eigen::Vector2d centre(axis[0] + (first ? 1 : -1) * l.offset, axis[1]);
    EXPECT_NEAR(lateral_distance(x, centre), first ? 1.2 : 1.1, 1e-6) << x.transpose();
    ++on_daughters;
  }
  EXPECT_GT(on_parent, 100);
  EXPECT_GT(on_daughters, 20);
}

// Where OpenCASCADE's fillets meet it leaves curves far shorter than the element size; meshed
// at h, the triangles beside them are slivers (the phase-separation split 3.7 / 2.4 at 75
// degrees, r = 0.8, h = 0.3: min angle 1.1 degrees, an edge of 0.0235). mesh_periodic_wall
// shrinks the triangles towards such curves: as good as the sharp example's 10 degrees.
TEST(Bifurcation, FilletedWallHasNoSlivers) {
  BifurcationSpec s;
  s.tube.diameter = 4.0;
  s.tube.axis = 2;
  s.tube.box = Eigen::Vector3d(16.0, 7.0, 20.0);
  s.tube.element_size = 0.3;
  s.daughter_diameters = {3.7, 2.4};
  s.angle_deg = 75.0;
  s.centre = 4.0;
  s.fillet_radius = 0.8;
  const VesselMesh wall = bifurcation(s);
  const MeshQuality q = check_mesh(wall);
  std::printf("split 3.7 / 2.4, fillet 0.8: %d nodes, min angle %.1f deg, edges %.4f..%.3f, largest fold %.1f deg\n",
              wall.surface.num_points(), q.min_angle_deg, q.min_edge, q.max_edge, q.max_fold_deg);
  EXPECT_GT(q.min_angle_deg, 10.0);
  EXPECT_LT(q.max_edge, 1.5 * s.tube.element_size);
}

// A fillet that does not fit the junction (here the creases around the split point are shorter
// than the radius) is an error naming the radius, not a broken wall.
TEST(Bifurcation, FilletThatDoesNotFitIsAnError) {
  BifurcationSpec s = example();
  s.fillet_radius = 1.0;
  try {
    bifurcation(s);
    FAIL() << "no error for fillet_radius 1";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("with fillet_radius 1;"), std::string::npos) << e.what();
  }
}

TEST(Bifurcation, InfeasibleLayoutsNameTheValue) {
  BifurcationSpec s = example();
  s.daughter_diameters = {3.0, 2.0};
  expect_invalid(s, "daughter diameter 3 must be in (0, 3)");
  s = example();
  s.angle_deg = 10.0;  // a shallow angle needs a long loop
  expect_invalid(s, "or widen the angle");
  s = example();
  s.tube.box[0] = 5.5;
  expect_invalid(s, "the box gives 2.75 (half its side x)");
  s = example();
  s.tube.box[2] = 5.0;
  expect_invalid(s, "must exceed twice the parent diameter");
  s = example();
  s.fillet_radius = 1.1;
  expect_invalid(s, "fillet radius 1.1 must be in [0, 1.1), below the smaller daughter's radius");
}
