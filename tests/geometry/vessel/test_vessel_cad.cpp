#include <gmsh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "geometry/vessel/gmsh_session.h"
#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"
#include "geometry/vessel/vessel.h"

using namespace rbcflow;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("rbcflow_test_vessel_cad_" + name)).string();
}

// A solid cylinder (with its end caps) written as CAD by gmsh's OpenCASCADE kernel: base centre
// x, direction d (its length), radius r. Generated here so the repository holds no binary CAD.
void write_cylinder(const std::string& path, const Eigen::Vector3d& x, const Eigen::Vector3d& d, double r) {
  GmshSession session;
  gmsh::model::occ::addCylinder(x[0], x[1], x[2], d[0], d[1], d[2], r);
  gmsh::model::occ::synchronize();
  gmsh::write(path);
  ASSERT_TRUE(std::filesystem::is_regular_file(path)) << "gmsh did not write " << path;
}

void expect_error(const VesselFileSpec& spec, const std::string& words) {
  try {
    import_cad_vessel(spec);
    FAIL() << "no error, expected one about " << words;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

// D = 3.5 in a 5 x 5 x 4 box, along z.
VesselFileSpec cylinder_spec(const std::string& path) {
  VesselFileSpec s;
  s.path = path;
  s.axis = 2;
  s.box = Eigen::Vector3d(5, 5, 4);
  s.element_size = 0.4;
  return s;
}

}  // namespace

// A STEP cylinder spanning the box becomes the periodic tube: caps dropped, nodes on the radius
// (OCC's exact cylinder), seam merged, normals into the lumen, as many triangles as tube() makes.
TEST(CadVessel, StepCylinderMeshesLikeTheTube) {
  const std::string path = temp_path("cylinder.step");
  write_cylinder(path, Eigen::Vector3d(2.5, 2.5, 0), Eigen::Vector3d(0, 0, 4), 1.75);
  const VesselFileSpec s = cylinder_spec(path);
  const VesselMesh wall = import_cad_vessel(s);
  std::filesystem::remove(path);
  EXPECT_EQ(wall.period, Eigen::Vector3d(0, 0, 4));
  EXPECT_LT(lumen_flux(wall), 0.0);
  for (int i = 0; i < wall.surface.num_points(); ++i) {
    const Eigen::Vector3d x = wall.surface.points.row(i);
    EXPECT_NEAR(std::hypot(x[0] - 2.5, x[1] - 2.5), 1.75, 1e-6 * 3.5) << x.transpose();
    EXPECT_GE(x[2], 0.0);
    EXPECT_LT(x[2], 4.0);
  }
  const MeshQuality q = check_mesh(wall);
  const double exact = std::numbers::pi * 3.5 * 4;
  EXPECT_NEAR(q.area, exact, 0.02 * exact);
  TubeSpec t;
  t.diameter = 3.5;
  t.box = s.box;
  t.element_size = s.element_size;
  const int tube_triangles = tube(t).surface.num_triangles();
  std::printf("STEP cylinder: %d triangles (tube builder %d), min angle %.1f deg\n", wall.surface.num_triangles(),
              tube_triangles, q.min_angle_deg);
  EXPECT_NEAR(wall.surface.num_triangles(), tube_triangles, 0.2 * tube_triangles);
  EXPECT_GT(q.min_angle_deg, 20.0);
}

// Along x, written at half size and scaled by 2 on import. (gmsh 4.8 writes no IGES, so the
// .iges/.igs path, the same OpenCASCADE import, has no test file.)
TEST(CadVessel, StepAlongXScaled) {
  const std::string path = temp_path("cylinder_x.stp");
  write_cylinder(path, Eigen::Vector3d(0, 1.25, 1.25), Eigen::Vector3d(2, 0, 0), 0.875);
  VesselFileSpec s = cylinder_spec(path);
  s.axis = 0;
  s.box = Eigen::Vector3d(4, 5, 5);
  s.scale = 2.0;
  const VesselMesh wall = vessel_file(s);  // .stp: the CAD import
  std::filesystem::remove(path);
  EXPECT_EQ(wall.period, Eigen::Vector3d(4, 0, 0));
  EXPECT_LT(lumen_flux(wall), 0.0);
  for (int i = 0; i < wall.surface.num_points(); ++i) {
    const Eigen::Vector3d x = wall.surface.points.row(i);
    EXPECT_NEAR(std::hypot(x[1] - 2.5, x[2] - 2.5), 1.75, 1e-6 * 3.5) << x.transpose();
  }
}

TEST(CadVessel, BadFilesGiveClearErrors) {
  const std::string empty = temp_path("empty.step");
  std::ofstream(empty).close();
  expect_error(cylinder_spec(empty), "is empty");
  std::filesystem::remove(empty);
  expect_error(cylinder_spec(temp_path("missing.step")), "does not exist");

  const std::string garbage = temp_path("garbage.step");
  std::ofstream(garbage) << "this is not STEP\n";
  expect_error(cylinder_spec(garbage), "garbage.step");
  std::filesystem::remove(garbage);

  const std::string short_path = temp_path("short.step");
  write_cylinder(short_path, Eigen::Vector3d(2.5, 2.5, 0), Eigen::Vector3d(0, 0, 3), 1.75);
  expect_error(cylinder_spec(short_path), "a periodic vessel must span the box side [0, 4]");
  std::filesystem::remove(short_path);
}
