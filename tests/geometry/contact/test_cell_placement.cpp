#include "geometry/contact/cell_placement.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "geometry/cgal/aabb_tree.h"
#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"
#include "geometry/contact/wall_distance.h"

using namespace rbcflow;

namespace {

constexpr double kGap = 0.05;

// The sampling of the placement's checks: check_order Gauss colatitudes, the surface untruncated.
TriangleMesh check_mesh(const SHSurface& s, int order) {
  return s.triangulate(SHTransform(s.order(), SphGrid::gauss(order, 2 * std::max(order, s.order())), 0));
}

// Smallest distance between the triangulations of a and b (b moved by `shift`), vertices of
// each to the triangles of the other; negative when a vertex lies inside the other cell.
double mesh_distance(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Vector3d& shift) {
  double smallest = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 2; ++pass) {
    const TriangleMesh& from = pass == 0 ? a : b;
    TriangleMesh to = pass == 0 ? b : a;
    const Eigen::Vector3d s = pass == 0 ? shift : Eigen::Vector3d(-shift);
    to.points.rowwise() += s.transpose();
    const TriangleAabbTree tree(to);
    for (int v = 0; v < from.num_points(); ++v) {
      const Eigen::Vector3d x = from.points.row(v).transpose();
      const TriangleAabbTree::ClosestPoint c = tree.closest_point(x);
      const auto t = to.triangles.row(c.triangle);
      const Eigen::Vector3d p0 = to.points.row(t[0]).transpose();
      const Eigen::Vector3d n = (to.points.row(t[1]).transpose() - p0).cross(to.points.row(t[2]).transpose() - p0);
      smallest = std::min(smallest, (x - c.point).dot(n) < 0 ? -c.distance : c.distance);
    }
  }
  return smallest;
}

// Smallest distance between any two placed cells over the 27 nearest periodic images.
double smallest_separation(const std::vector<SHSurface>& cells, const Eigen::Vector3d& box, int order) {
  std::vector<TriangleMesh> meshes;
  for (const SHSurface& s : cells) meshes.push_back(check_mesh(s, order));
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    for (std::size_t j = i; j < meshes.size(); ++j) {
      for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b)
          for (int c = -1; c <= 1; ++c) {
            if (i == j && a == 0 && b == 0 && c == 0) continue;
            const Eigen::Vector3d shift = box.cwiseProduct(Eigen::Vector3d(a, b, c));
            const Eigen::Vector3d d = meshes[j].points.colwise().mean().transpose() + shift -
                                      meshes[i].points.colwise().mean().transpose();
            if (d.norm() > 4.0) continue;  // cells of diameter < 3 (rbc 2.77) cannot meet
            smallest = std::min(smallest, mesh_distance(meshes[i], meshes[j], shift));
          }
    }
  }
  return smallest;
}

double smallest_wall_distance(const std::vector<SHSurface>& cells, const WallDistance& wall, int order) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const SHSurface& s : cells) {
    const TriangleMesh m = check_mesh(s, order);
    for (int v = 0; v < m.num_points(); ++v)
      smallest = std::min(smallest, wall.closest(m.points.row(v).transpose()).signed_distance);
  }
  return smallest;
}

// The same over the points the solver uses: each cell's own grid (Gauss, N x 2N), between the
// check mesh's vertices.
double smallest_grid_wall_distance(const std::vector<SHSurface>& cells, const WallDistance& wall) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const SHSurface& s : cells) {
    const Eigen::MatrixX3d x = s.geometry(SHTransform::gauss(s.order())).x;
    for (Eigen::Index v = 0; v < x.rows(); ++v)
      smallest = std::min(smallest, wall.closest(x.row(v).transpose()).signed_distance);
  }
  return smallest;
}

VesselMesh tube_3_5() { return tube(TubeSpec{3.5, 2, Eigen::Vector3d(4, 4, 8), 0.25}); }

}  // namespace

TEST(CellPlacement, SpheresInAPeriodicBoxDoNotOverlap) {
  PlacementSpec spec;
  spec.box = Eigen::Vector3d(6, 6, 6);
  spec.count = 12;
  spec.gap = kGap;
  spec.seed = 3;
  const SHSurface sphere = make_sphere(8);
  const Placement p = place_cells(sphere, spec, nullptr);
  ASSERT_EQ(static_cast<int>(p.cells.size()), spec.count);
  EXPECT_EQ(p.compression_sweeps, 0);
  EXPECT_NEAR(p.hematocrit, 12 * 4.0 / 3.0 * std::numbers::pi / 216.0, 1e-3);
  EXPECT_GE(smallest_separation(placed_surfaces(sphere, p.cells), spec.box, spec.check_order), kGap);
}

// 9 unit spheres in a periodic box of side 4.5 (volume fraction 0.41, 0.45 counting the gap):
// beyond the jamming of random sequential addition (0.38 for spheres), reached by compression.
TEST(CellPlacement, CompressionGoesBeyondSequentialAddition) {
  PlacementSpec spec;
  spec.box = Eigen::Vector3d(4.5, 4.5, 4.5);
  spec.count = 9;
  spec.gap = kGap;
  const SHSurface sphere = make_sphere(8);
  const Placement p = place_cells(sphere, spec, nullptr);
  std::printf("9 spheres: volume fraction %.3f after %d compression sweeps\n", p.hematocrit, p.compression_sweeps);
  ASSERT_EQ(static_cast<int>(p.cells.size()), spec.count);
  EXPECT_GT(p.compression_sweeps, 0);
  EXPECT_GE(smallest_separation(placed_surfaces(sphere, p.cells), spec.box, spec.check_order), kGap);
}

// The paper's hematocrit H_T = 0.30 (section 11.2) in a D = 3.5 tube: 6 Evans-Fung cells in
// a length of 8 (H_T = 0.33 with the polyhedral lumen), stacked as coins (automatic
// orientation, D < 1.3 cell diameters).
TEST(CellPlacement, TubeHematocrit030InTube35) {
  const VesselMesh wall = tube_3_5();
  const WallDistance distance(wall);
  PlacementSpec spec;
  spec.box = Eigen::Vector3d(4, 4, 8);
  spec.count = 6;
  spec.gap = kGap;
  spec.seed = 1;
  const SHSurface rbc = make_biconcave(12);
  const auto start = std::chrono::steady_clock::now();
  const Placement p = place_cells(rbc, spec, &wall);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("6 cells in the D = 3.5 tube: H_T = %.3f, %d compression sweeps, %.2f s\n", p.hematocrit,
              p.compression_sweeps, seconds);
  ASSERT_EQ(static_cast<int>(p.cells.size()), spec.count);
  EXPECT_GE(p.hematocrit, 0.30);
  const std::vector<SHSurface> cells = placed_surfaces(rbc, p.cells);
  EXPECT_GE(smallest_separation(cells, spec.box, spec.check_order), kGap);
  EXPECT_GE(smallest_wall_distance(cells, distance, spec.check_order), kGap);
  EXPECT_GE(smallest_grid_wall_distance(cells, distance), kGap);
}

// A bifurcation whose narrower daughter (D = 2.7) is narrower than the cell (diameter 2.77):
// 15 cells (H_T = 0.22) do not fit by random sequential addition (8 do, seed 1), and a
// compression that let shrunken cells wait in that daughter stopped at 96% of full size after 534
// sweeps. With the wall tested at full size throughout, every cell is placed, clear of the wall
// and of every other cell by the gap.
TEST(CellPlacement, BifurcationWithADaughterNarrowerThanTheCell) {
  BifurcationSpec b;
  b.tube = TubeSpec{4.0, 2, Eigen::Vector3d(16, 7, 20), 0.3};
  b.daughter_diameters = {3.5, 2.7};
  b.angle_deg = 75.0;
  b.centre = 4.0;
  const VesselMesh wall = bifurcation(b);
  const WallDistance distance(wall);
  PlacementSpec spec;
  spec.box = b.tube.box;
  spec.count = 15;
  spec.gap = 0.02;
  spec.seed = 1;
  const SHSurface rbc = make_biconcave(8);
  const Placement p = place_cells(rbc, spec, &wall);
  std::printf("15 cells in the bifurcation: H_T = %.3f, %d compression sweeps\n", p.hematocrit, p.compression_sweeps);
  ASSERT_EQ(static_cast<int>(p.cells.size()), spec.count);
  EXPECT_GT(p.compression_sweeps, 0);
  const std::vector<SHSurface> cells = placed_surfaces(rbc, p.cells);
  EXPECT_GE(smallest_separation(cells, spec.box, spec.check_order), spec.gap);
  EXPECT_GE(smallest_wall_distance(cells, distance, spec.check_order), spec.gap);
  EXPECT_GE(smallest_grid_wall_distance(cells, distance), spec.gap);
}

TEST(CellPlacement, SameSeedSamePlacement) {
  PlacementSpec spec;
  spec.box = Eigen::Vector3d(5, 5, 5);
  spec.count = 6;
  spec.gap = kGap;
  spec.seed = 42;
  const SHSurface rbc = make_biconcave(8);
  const Placement a = place_cells(rbc, spec, nullptr), b = place_cells(rbc, spec, nullptr);
  spec.seed = 43;
  const Placement c = place_cells(rbc, spec, nullptr);
  ASSERT_EQ(a.cells.size(), b.cells.size());
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    EXPECT_TRUE(a.cells[i].position == b.cells[i].position);
    EXPECT_TRUE(a.cells[i].rotation == b.cells[i].rotation);
  }
  EXPECT_FALSE(a.cells[0].position == c.cells[0].position);
}

// Narrow tubes (D = 3 < 1.3 x 2.75) get the cells' symmetry axes along the tube axis.
TEST(CellPlacement, NarrowTubeAlignsCellsWithTheAxis) {
  const VesselMesh wall = tube(TubeSpec{3.0, 2, Eigen::Vector3d(3.5, 3.5, 6), 0.2});
  PlacementSpec spec;
  spec.box = Eigen::Vector3d(3.5, 3.5, 6);
  spec.count = 4;
  spec.gap = 0.02;
  const Placement p = place_cells(make_biconcave(8), spec, &wall);
  ASSERT_EQ(p.cells.size(), 4u);
  for (const PlacedCell& c : p.cells) EXPECT_NEAR(std::abs(c.rotation(2, 2)), 1.0, 1e-12);
}

// An undeformed red cell (diameter 2.77) fits a D = 2 tube in no orientation: the cells are
// stacked along the axis at equal spacing and pre-deformed. Common checks of both starts: the
// rest shapes are the reference turned, so they keep its area; the initial shapes keep the
// cell's volume and sit on the axis at spacing L / n; every initial shape is at least the gap
// inside the wall and from the others (checked on the triangulations, independently of the
// placement's own test).
namespace {

void expect_stacked_on_the_axis(const SHSurface& rbc, const Placement& p, const PlacementSpec& spec,
                                const VesselMesh& wall, double volume_tolerance) {
  const SHTransform t = SHTransform::gauss(24);
  const double volume = enclosed_volume(rbc.geometry(t)), area = surface_area(rbc.geometry(t));
  const std::vector<SHSurface> rest = placed_surfaces(rbc, p.cells), initial = initial_surfaces(rbc, p);
  const double spacing = spec.box.z() / spec.count;
  for (std::size_t i = 0; i < p.cells.size(); ++i) {
    EXPECT_NEAR(enclosed_volume(initial[i].geometry(t)) / volume, 1.0, volume_tolerance);
    EXPECT_NEAR(surface_area(rest[i].geometry(t)) / area, 1.0, 1e-12);
    const Eigen::Vector3d c = volume_centroid(initial[i].geometry(t));
    EXPECT_NEAR(c.x(), 0.5 * spec.box.x(), 0.02);  // on the axis (the mean of the wall's nodes)
    EXPECT_NEAR(c.y(), 0.5 * spec.box.y(), 0.02);
    const double dz = std::fmod(c.z() - volume_centroid(initial[0].geometry(t)).z() + spec.box.z(), spacing);
    EXPECT_NEAR(std::min(dz, spacing - dz), 0.0, 1e-9);
  }
  EXPECT_GE(smallest_separation(initial, spec.box, spec.check_order), spec.gap);
  EXPECT_GE(smallest_wall_distance(initial, WallDistance(wall), spec.check_order), spec.gap);
}

}  // namespace

// Edge-on (the default): the stretch is symmetric with determinant 1 (the volume kept to rounding) and keeps
// the faces' area (s_axis s_width = 1, the thickness unchanged) where the spacing allows.
TEST(CellPlacement, NarrowTubeGetsStackedStretchedCells) {
  const Eigen::Vector3d box(2.5, 2.5, 9);
  const VesselMesh wall = tube(TubeSpec{2.0, 2, box, 0.2});
  PlacementSpec spec;
  spec.box = box;
  spec.count = 2;  // H_T = 0.30, as data/cases/fahraeus/quick/tube_2_0.toml
  spec.gap = kGap;
  const SHSurface rbc = make_biconcave(12);
  const Placement p = place_cells(rbc, spec, &wall);
  ASSERT_EQ(p.cells.size(), 2u);
  EXPECT_FALSE(p.parachute);
  const Eigen::Vector3d& f = p.stretch_factors;
  std::printf("D = 2, 2 cells: stretch %.3f along, %.3f across, %.3f through the thickness\n", f[0], f[1], f[2]);
  EXPECT_LT(f[1], 1.0);  // squeezed across the tube
  EXPECT_NEAR(f[0] * f[1], 1.0, 1e-12);
  EXPECT_NEAR(f[2], 1.0, 1e-12);
  for (const PlacedCell& c : p.cells) {
    const Eigen::Matrix3d& S = c.stretch;
    EXPECT_LT((S - S.transpose()).norm(), 1e-14);
    EXPECT_NEAR(S.determinant(), 1.0, 1e-12);
    EXPECT_NEAR((S * c.rotation.col(0)).dot(c.rotation.col(0)), f[0], 1e-12);  // the disc's plane along the axis
    EXPECT_NEAR(std::abs(c.rotation.col(0).z()), 1.0, 1e-12);
  }
  expect_stacked_on_the_axis(rbc, p, spec, wall, 1e-12);
}

// Face-on: the cells are the placement's parachute, its nose along the flow (here
// -z), its volume that of the cell (exact: geometry/surface/parachute_fold.h), its outer radius within
// the lumen less the margin and gap.
TEST(CellPlacement, NarrowTubeGetsStackedParachutes) {
  const Eigen::Vector3d box(2.5, 2.5, 9);
  const VesselMesh wall = tube(TubeSpec{2.0, 2, box, 0.2});
  PlacementSpec spec;
  spec.box = box;
  spec.count = 2;
  spec.gap = kGap;
  spec.flow = Eigen::Vector3d(0, 0, -5);
  spec.narrow_start = NarrowStart::parachute;
  const SHSurface rbc = make_biconcave(12);
  const Placement p = place_cells(rbc, spec, &wall);
  ASSERT_EQ(p.cells.size(), 2u);
  ASSERT_TRUE(p.parachute);
  std::printf("D = 2, 2 cells: parachutes of radius %.3f, length %.3f\n", p.parachute_radius, p.parachute_length);
  EXPECT_EQ(p.stretch_factors, Eigen::Vector3d::Ones());
  EXPECT_LT(p.parachute_radius, 1.0 - kGap);
  EXPECT_GT(p.parachute_radius, 0.8);  // fills the lumen: (1 - 0.05) x 1 - gap less the overshoot
  for (const PlacedCell& c : p.cells) EXPECT_NEAR(c.rotation.col(2).z(), -1.0, 1e-12);  // the nose along -z
  expect_stacked_on_the_axis(rbc, p, spec, wall, 1e-12);
}

// A tube narrower than even a pre-deformed cell is an error that says so; asked for
// parachutes, it names both attempts (the fold's radius is too small for the cell there).
TEST(CellPlacement, TubeTooNarrowEvenForPreDeformedCellsIsAnError) {
  const VesselMesh wall = tube(TubeSpec{1.0, 2, Eigen::Vector3d(1.5, 1.5, 8), 0.15});
  for (const NarrowStart start : {NarrowStart::stretched, NarrowStart::parachute}) {
    PlacementSpec spec;
    spec.box = Eigen::Vector3d(1.5, 1.5, 8);
    spec.count = 1;
    spec.gap = 0.02;
    spec.narrow_start = start;
    try {
      place_cells(make_biconcave(8), spec, &wall);
      FAIL() << "a red cell should not fit a D = 1 tube";
    } catch (const std::runtime_error& e) {
      std::printf("%s\n", e.what());
      const std::string what = e.what();
      EXPECT_NE(what.find("too narrow"), std::string::npos);
      if (start == NarrowStart::parachute) {
        EXPECT_NE(what.find("; face-on: "), std::string::npos);
        EXPECT_NE(what.find("too small for the cell"), std::string::npos);
      }
    }
  }
}

TEST(CellPlacement, ImpossibleRequestSaysHowManyFitted) {
  const VesselMesh wall = tube_3_5();
  PlacementSpec spec;
  spec.box = Eigen::Vector3d(4, 4, 8);
  spec.count = 20;  // H_T = 1.09
  spec.gap = kGap;
  try {
    place_cells(make_biconcave(8), spec, &wall);
    FAIL() << "20 cells should not fit";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("of 20 cells fit"), std::string::npos);
    EXPECT_NE(what.find("hematocrit"), std::string::npos);
  }
  spec.box = Eigen::Vector3d(0, 4, 8);
  EXPECT_THROW(place_cells(make_biconcave(8), spec, &wall), std::invalid_argument);
}
