#include "io/vtk_polydata.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

TEST(VtkPolyData, RoundTripKeepsPointsAndTriangles) {
  const SHTransform t = SHTransform::gauss(8);
  const TriangleMesh mesh = make_biconcave(8).triangulate(t);
  const auto dir = std::filesystem::temp_directory_path() / "rbcflow_test_vtp";
  std::filesystem::create_directories(dir);
  const auto path = dir / "cell.vtp";
  write_vtp(path, mesh, {{"scalar", Eigen::MatrixXd::Ones(mesh.num_points(), 1)}});
  const TriangleMesh back = read_vtp(path);
  EXPECT_EQ(back.triangles, mesh.triangles);
  EXPECT_EQ((back.points - mesh.points).cwiseAbs().maxCoeff(), 0.0);
  // No temporary left behind by the atomic write.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  std::filesystem::remove_all(dir);
}

TEST(VtkPolyData, FieldOfWrongSizeIsRejectedAndEarlierFileKept) {
  const TriangleMesh mesh = make_sphere(4).triangulate(SHTransform::gauss(4));
  const auto path = std::filesystem::temp_directory_path() / "rbcflow_test_keep.vtp";
  write_vtp(path, mesh);
  EXPECT_THROW(write_vtp(path, mesh, {{"bad", Eigen::MatrixXd::Ones(3, 1)}}), std::invalid_argument);
  EXPECT_EQ(read_vtp(path).num_points(), mesh.num_points());
  std::filesystem::remove(path);
}

TEST(VtkPolyData, MissingFileAndMissingDirectoryAreClearErrors) {
  EXPECT_THROW(read_vtp("/nonexistent/cell.vtp"), std::runtime_error);
  const TriangleMesh mesh = make_sphere(4).triangulate(SHTransform::gauss(4));
  try {
    write_vtp("/nonexistent-dir/cell.vtp", mesh);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir"), std::string::npos) << e.what();
  }
}

TEST(VtkPolyData, SurfaceReadsBackWithItsPointData) {
  const TriangleMesh mesh = make_sphere(4).triangulate(SHTransform::gauss(4));
  const auto path = std::filesystem::temp_directory_path() / "rbcflow_test_surface.vtp";
  Eigen::MatrixXd v(mesh.num_points(), 3);
  v.setRandom();
  write_vtp(path, mesh, {{"velocity", v}, {"J_S", Eigen::MatrixXd::Constant(mesh.num_points(), 1, 1.5)}});
  const Surface s = read_vtp_surface(path, "cells");
  EXPECT_EQ(s.name, "cells");
  EXPECT_EQ(s.mesh.triangles, mesh.triangles);
  ASSERT_EQ(s.fields.size(), 2u);
  EXPECT_EQ(s.fields[0].name, "velocity");
  EXPECT_EQ((s.fields[0].values - v).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(s.fields[1].name, "J_S");
  EXPECT_EQ(s.fields[1].values.cols(), 1);
  std::filesystem::remove(path);
}
