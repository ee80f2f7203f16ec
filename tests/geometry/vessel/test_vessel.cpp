#include "geometry/vessel/vessel.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/cgal/aabb_tree.h"
#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"

using namespace rbcflow;

namespace {

TubeSpec small_tube(int axis = 2) {
  TubeSpec s;
  s.diameter = 3.5;
  s.axis = axis;
  s.box = Eigen::Vector3d(5.0, 5.0, 5.0);
  s.box[axis] = 4.0;
  s.element_size = 0.4;
  return s;
}

// Distance of x from the axis of a tube along `axis` centred in the box.
double radius(const Eigen::Vector3d& x, const TubeSpec& s) {
  Eigen::Vector3d d = x - 0.5 * s.box;
  d[s.axis] = 0;
  return d.norm();
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("rbcflow_test_vessel_" + name)).string();
}

// The triangles unwrapped one by one (three own nodes each), for the non-periodic AABB tree.
TriangleMesh unwrapped(const VesselMesh& wall) {
  TriangleMesh m;
  m.points.resize(3 * wall.surface.num_triangles(), 3);
  m.triangles.resize(wall.surface.num_triangles(), 3);
  for (int t = 0; t < wall.surface.num_triangles(); ++t) {
    m.points.middleRows<3>(3 * t) = triangle_vertices(wall, t).transpose();
    m.triangles.row(t) = Eigen::RowVector3i(3 * t, 3 * t + 1, 3 * t + 2);
  }
  return m;
}

void expect_error(const VesselMesh& wall, const std::string& words) {
  try {
    check_mesh(wall);
    FAIL() << "no error, expected one about " << words;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Vessel, TubeNodesOnTheRadiusForEveryAxis) {
  for (int axis = 0; axis < 3; ++axis) {
    const TubeSpec s = small_tube(axis);
    const VesselMesh wall = tube(s);
    EXPECT_EQ(wall.period[axis], s.box[axis]);
    for (int i = 0; i < wall.surface.num_points(); ++i) {
      const Eigen::Vector3d x = wall.surface.points.row(i);
      EXPECT_NEAR(radius(x, s), 0.5 * s.diameter, 1e-8 * s.diameter);
      EXPECT_GE(x[axis], 0.0);
      EXPECT_LT(x[axis], s.box[axis]);  // seam merged: no node on the far end face
    }
  }
}

TEST(Vessel, GmshKeepsTheOpenMpThreadCount) {
  omp_set_num_threads(2);
  tube(small_tube());
  EXPECT_EQ(omp_get_max_threads(), 2);
}

// The merged seam leaves a closed surface (no boundary edge, checked by check_mesh) whose
// normals point to the axis and whose area is that of the inscribed polyhedral cylinder.
TEST(Vessel, PeriodicSeamClosesTheTube) {
  const TubeSpec s = small_tube();
  const VesselMesh wall = tube(s);
  const MeshQuality q = check_mesh(wall);
  EXPECT_GT(q.min_angle_deg, 20.0);
  EXPECT_LT(q.max_edge, 1.5 * s.element_size);
  const double exact = std::numbers::pi * s.diameter * s.box[2];
  EXPECT_NEAR(q.area, exact, 0.02 * exact);
  for (int t = 0; t < wall.surface.num_triangles(); ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    Eigen::Vector3d radial = v.rowwise().mean() - 0.5 * s.box;
    radial[2] = 0;
    EXPECT_LT((v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).dot(radial), 0.0) << t;
  }
}

TEST(Vessel, ConstrictionNodesOnTheProfile) {
  ConstrictionSpec s;
  s.tube = small_tube();
  s.tube.box[2] = 8.0;
  s.depth = 1.0;
  s.width = 1.0;
  s.centre = 4.0;
  const VesselMesh wall = constriction(s);
  check_mesh(wall);
  double narrowest = INFINITY;
  for (int i = 0; i < wall.surface.num_points(); ++i) {
    const Eigen::Vector3d x = wall.surface.points.row(i);
    // The spline through 201 profile points interpolates d(z) to ~1e-6 (gmsh 4.8's OCC spline:
    // 8e-5 at 81 points, 4e-6 at 161).
    EXPECT_NEAR(radius(x, s.tube), 0.5 * s.diameter(x[2]), 1e-5 * s.tube.diameter) << x.transpose();
    narrowest = std::min(narrowest, 2 * radius(x, s.tube));
  }
  EXPECT_NEAR(narrowest, s.tube.diameter - s.depth, 0.02);
}

TEST(Vessel, StlRoundTripKeepsTheTriangles) {
  VesselMesh wall = tube(small_tube());
  wall.period.setZero();  // STL keeps no periodicity: write the open tube as a plain mesh
  const std::string path = temp_path("tube.stl");
  write_vessel(wall, path);
  // The open tube is not closed without its period; read it back periodic.
  const VesselMesh back = read_vessel(path, Eigen::Vector3d(0, 0, 4.0));
  std::filesystem::remove(path);
  ASSERT_EQ(back.surface.num_triangles(), wall.surface.num_triangles());
  ASSERT_EQ(back.surface.num_points(), wall.surface.num_points());
  double total = 0, total_back = 0;
  for (int t = 0; t < wall.surface.num_triangles(); ++t) {
    total += triangle_vertices(VesselMesh{wall.surface, Eigen::Vector3d(0, 0, 4)}, t).sum();
    total_back += triangle_vertices(back, t).sum();
  }
  EXPECT_NEAR(total_back, total, 1e-5 * std::abs(total));  // STL stores floats
}

TEST(Vessel, MshRoundTripIsExact) {
  const VesselMesh wall = tube(small_tube());
  const std::string path = temp_path("tube.msh");
  write_vessel(wall, path);
  const VesselMesh back = read_vessel(path, wall.period);
  std::filesystem::remove(path);
  ASSERT_EQ(back.surface.num_triangles(), wall.surface.num_triangles());
  for (int t = 0; t < wall.surface.num_triangles(); ++t)
    EXPECT_LT((triangle_vertices(back, t) - triangle_vertices(wall, t)).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Vessel, BadMeshesGiveClearErrors) {
  const VesselMesh good = tube(small_tube());
  VesselMesh hole = good;
  hole.surface.triangles.conservativeResize(good.surface.num_triangles() - 1, 3);
  expect_error(hole, "hole");
  VesselMesh flipped = good;
  flipped.surface.triangles.row(7) = Eigen::RowVector3i(good.surface.triangles(7, 0),
                                                        good.surface.triangles(7, 2),
                                                        good.surface.triangles(7, 1));
  expect_error(flipped, "flipped triangle");
  VesselMesh extra = good;  // a third triangle on the edge of triangle 0
  extra.surface.points.conservativeResize(good.surface.num_points() + 1, 3);
  extra.surface.points.row(good.surface.num_points()) = Eigen::RowVector3d(2.5, 2.5, 2.0);
  extra.surface.triangles.conservativeResize(good.surface.num_triangles() + 1, 3);
  extra.surface.triangles.row(good.surface.num_triangles()) = Eigen::RowVector3i(
      good.surface.triangles(0, 0), good.surface.triangles(0, 1), good.surface.num_points());
  expect_error(extra, "not manifold");
  VesselMesh duplicate = good;
  duplicate.surface.points.row(3) = duplicate.surface.points.row(5);
  expect_error(duplicate, "duplicate nodes");
  expect_error(VesselMesh{}, "empty");

  const std::string path = temp_path("empty.stl");
  std::ofstream(path).close();
  EXPECT_THROW(
      {
        try {
          read_vessel(path);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("is empty"), std::string::npos) << e.what();
          throw;
        }
      },
      std::runtime_error);
  std::filesystem::remove(path);
  EXPECT_THROW(read_vessel(temp_path("missing.msh")), std::runtime_error);
}

// The closest-point distance from points inside the tube to the polyhedral wall approaches
// the distance R - r to the cylinder at second order in the element size (chord sag h^2/8R).
TEST(Vessel, AabbDistanceToTubeConvergesAtSecondOrder) {
  double previous = 0, previous_h = 0;
  for (double h : {0.4, 0.2, 0.1}) {
    TubeSpec s = small_tube();
    s.element_size = h;
    const VesselMesh wall = tube(s);
    const TriangleAabbTree tree(unwrapped(wall));
    double error = 0;
    for (int k = 0; k < 40; ++k) {
      const double angle = 0.37 * k, r = 0.3 + 0.03 * k, z = 1.0 + 0.05 * k;
      const Eigen::Vector3d x(2.5 + r * std::cos(angle), 2.5 + r * std::sin(angle), z);
      error = std::max(error, std::abs(tree.closest_point(x).distance - (0.5 * s.diameter - r)));
    }
    std::printf("h = %.2f  max |distance error| = %.3e\n", h, error);
    if (previous > 0) {
      const double order = std::log(previous / error) / std::log(previous_h / h);
      EXPECT_GT(order, 1.6) << "h = " << h;
    }
    previous = error;
    previous_h = h;
  }
}

// A periodic mesh written with its seam on both box faces (as CAD tools export a tube) and with
// outward normals: read_vessel merges the copies modulo the period and turns the normals into
// the lumen; `scale` multiplies the coordinates.
TEST(Vessel, ReadMergesPeriodicCopiesAndOrientsIntoTheLumen) {
  const VesselMesh wall = tube(small_tube());
  VesselMesh open;  // nodes at the unwrapped positions: those past the far face are copies
  std::vector<Eigen::Vector3d> nodes;
  open.surface.triangles.resize(wall.surface.num_triangles(), 3);
  for (int t = 0; t < wall.surface.num_triangles(); ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    for (int a = 0; a < 3; ++a) {
      int k = 0;
      while (k < static_cast<int>(nodes.size()) && (nodes[k] - v.col(a)).norm() > 1e-12) ++k;
      if (k == static_cast<int>(nodes.size())) nodes.push_back(v.col(a));
      open.surface.triangles(t, a == 0 ? 0 : 3 - a) = k;  // reversed: normals out of the lumen
    }
  }
  open.surface.points.resize(static_cast<int>(nodes.size()), 3);
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) open.surface.points.row(i) = nodes[i].transpose();
  ASSERT_GT(open.surface.num_points(), wall.surface.num_points());  // the seam copies
  EXPECT_GT(lumen_flux(VesselMesh{open.surface, wall.period}), 0.0);

  const std::string path = temp_path("open_tube.msh");
  write_vessel(open, path);
  const VesselMesh back = read_vessel(path, 2.0 * wall.period, 2.0);
  std::filesystem::remove(path);
  EXPECT_EQ(back.surface.num_points(), wall.surface.num_points());
  EXPECT_EQ(back.surface.num_triangles(), wall.surface.num_triangles());
  EXPECT_LT(lumen_flux(back), 0.0);
  EXPECT_NEAR(check_mesh(back).area, 4.0 * check_mesh(wall).area, 1e-12 * check_mesh(back).area);
}

// For ParaView: no triangle spans the box (seam nodes copied), the same triangles and area.
TEST(Vessel, DrawableSurfaceHasNoTriangleAcrossTheBox) {
  const VesselMesh wall = tube(small_tube());
  const MeshQuality q = check_mesh(wall);
  const TriangleMesh d = drawable_surface(wall);
  ASSERT_EQ(d.num_triangles(), wall.surface.num_triangles());
  EXPECT_GT(d.num_points(), wall.surface.num_points());
  double area = 0, longest = 0;
  for (int t = 0; t < d.num_triangles(); ++t) {
    Eigen::Matrix3d v;
    for (int a = 0; a < 3; ++a) v.col(a) = d.points.row(d.triangles(t, a)).transpose();
    EXPECT_LT((v - triangle_vertices(wall, t)).cwiseAbs().maxCoeff(), 1e-14);
    area += 0.5 * (v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).norm();
    for (int a = 0; a < 3; ++a) longest = std::max(longest, (v.col((a + 1) % 3) - v.col(a)).norm());
  }
  EXPECT_NEAR(area, q.area, 1e-12 * q.area);
  EXPECT_LE(longest, q.max_edge + 1e-12);
}

// The same defects in a mesh file: the error names the file and the problem.
TEST(Vessel, BadMeshFilesNameTheFileAndTheProblem) {
  const VesselMesh good = tube(small_tube());
  auto expect_file_error = [&](const VesselMesh& bad, const std::string& name, const std::string& words) {
    const std::string path = temp_path(name);
    write_vessel(VesselMesh{bad.surface, Eigen::Vector3d::Zero()}, path);
    try {
      read_vessel(path, good.period);
      ADD_FAILURE() << "no error, expected one about " << words;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
  };
  VesselMesh hole = good;
  hole.surface.triangles.conservativeResize(good.surface.num_triangles() - 1, 3);
  expect_file_error(hole, "hole.msh", "has a hole");
  VesselMesh flipped = good;
  flipped.surface.triangles.row(7) = Eigen::RowVector3i(good.surface.triangles(7, 0), good.surface.triangles(7, 2),
                                                        good.surface.triangles(7, 1));
  expect_file_error(flipped, "flipped.msh", "flipped triangle");
  VesselMesh extra = good;  // a third triangle on the edge of triangle 0
  extra.surface.points.conservativeResize(good.surface.num_points() + 1, 3);
  extra.surface.points.row(good.surface.num_points()) = Eigen::RowVector3d(2.5, 2.5, 2.0);
  extra.surface.triangles.conservativeResize(good.surface.num_triangles() + 1, 3);
  extra.surface.triangles.row(good.surface.num_triangles()) = Eigen::RowVector3i(
      good.surface.triangles(0, 0), good.surface.triangles(0, 1), good.surface.num_points());
  expect_file_error(extra, "nonmanifold.stl", "not manifold");

  const std::string empty = temp_path("empty.msh");
  std::ofstream(empty).close();
  try {
    read_vessel(empty, good.period);
    ADD_FAILURE() << "no error for an empty file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(empty + " is empty"), std::string::npos) << e.what();
  }
  std::filesystem::remove(empty);
}
