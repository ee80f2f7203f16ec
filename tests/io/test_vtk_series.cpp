// VTK XML series: .vtp per surface per frame and the .pvd collection, read back with VTK's
// own readers; restarts; reading a chosen frame.
#include "io/vtk_series.h"

#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <fstream>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<Surface> frame(double t) {
  const SHTransform tr = SHTransform::gauss(6);
  SHSurface s = make_sphere(6);
  s.translate(Eigen::Vector3d(0, 0, t));
  Surface cells{"cells", s.triangulate(tr), {}};
  const int n = cells.mesh.num_points();
  cells.fields.push_back({"velocity", Eigen::MatrixXd::Constant(n, 3, t)});
  cells.fields.push_back({"tension", Eigen::VectorXd::LinSpaced(n, 0, 1)});
  Surface wall{"wall", make_sphere(6, 5.0).triangulate(tr), {}};
  wall.fields.push_back({"traction", Eigen::MatrixXd::Constant(wall.mesh.num_points(), 3, t)});
  return {cells, wall};
}

}  // namespace

TEST(VtkSeries, FramesReadBackWithVtkReaders) {
  const fs::path dir = fresh_dir("rbcflow_test_vtk_series");
  VtkSeriesWriter w(dir);
  w.write_frame(0, 0.0, frame(0.0));
  w.write_frame(100, 0.5, frame(0.5));
  ASSERT_TRUE(fs::exists(dir / "vtk" / "cells_00000100.vtp"));
  ASSERT_TRUE(fs::exists(dir / "vtk" / "wall_00000100.vtp"));

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir / "vtk" / "cells_00000100.vtp").c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  const Surface expected = frame(0.5)[0];
  ASSERT_EQ(poly->GetNumberOfPoints(), expected.mesh.num_points());
  EXPECT_EQ(poly->GetNumberOfPolys(), expected.mesh.num_triangles());
  double x[3];
  poly->GetPoint(7, x);
  EXPECT_EQ(x[2], expected.mesh.points(7, 2));
  ASSERT_TRUE(poly->GetPointData()->GetArray("velocity"));
  EXPECT_EQ(poly->GetPointData()->GetArray("velocity")->GetNumberOfComponents(), 3);
  EXPECT_EQ(poly->GetPointData()->GetArray("tension")->GetComponent(5, 0), expected.fields[1].values(5, 0));

  const std::vector<VtkSeriesEntry> entries = read_pvd(dir / "rbcflow.pvd");
  ASSERT_EQ(entries.size(), 4u);
  EXPECT_EQ(entries[2].step, 100);
  EXPECT_EQ(entries[2].time, 0.5);
  EXPECT_EQ(entries[3].surface, "wall");
  EXPECT_EQ(entries[3].file, "vtk/wall_00000100.vtp");  // relative to the .pvd
  fs::remove_all(dir);
}

TEST(VtkSeries, ReadFrameGivesTheSurfacesWithTheirFields) {
  const fs::path dir = fresh_dir("rbcflow_test_vtk_frame");
  VtkSeriesWriter w(dir);
  w.write_frame(0, 0.0, frame(0.0));
  w.write_frame(10, 0.1, frame(0.1));
  const VtkFrame last = read_vtk_frame(dir);
  EXPECT_EQ(last.step, 10);
  EXPECT_EQ(last.time, 0.1);
  ASSERT_EQ(last.surfaces.size(), 2u);
  EXPECT_EQ(last.surfaces[0].name, "cells");
  ASSERT_EQ(last.surfaces[0].fields.size(), 2u);
  EXPECT_EQ(last.surfaces[0].fields[0].name, "velocity");
  EXPECT_EQ(last.surfaces[0].fields[0].values(3, 1), 0.1);
  EXPECT_EQ(read_vtk_frame(dir, 0).surfaces[1].name, "wall");
  try {
    read_vtk_frame(dir, 5);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no frame at step 5"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("saved steps: 0 10"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(VtkSeries, RestartDropsLaterFrames) {
  const fs::path dir = fresh_dir("rbcflow_test_vtk_restart");
  {
    VtkSeriesWriter w(dir);
    for (long s : {0, 10, 20}) w.write_frame(s, 0.01 * s, frame(0.01 * s));
  }
  VtkSeriesWriter w(dir, 10);
  EXPECT_EQ(w.entries().size(), 4u);
  EXPECT_FALSE(fs::exists(dir / "vtk" / "cells_00000020.vtp"));
  EXPECT_THROW(w.write_frame(10, 0.1, frame(0.1)), std::invalid_argument);
  w.write_frame(15, 0.15, frame(0.15));
  EXPECT_EQ(read_pvd(dir / "rbcflow.pvd").back().step, 15);
}

TEST(VtkSeries, MissingOrForeignCollectionIsAClearError) {
  const fs::path dir = fresh_dir("rbcflow_test_vtk_bad");
  EXPECT_THROW(read_vtk_frame(dir), std::runtime_error);
  std::ofstream(dir / "rbcflow.pvd") << "<html></html>";
  try {
    read_vtk_frame(dir);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not a VTK collection"), std::string::npos) << e.what();
  }
  { VtkSeriesWriter fresh(dir); }
  EXPECT_THROW(read_vtk_frame(dir), std::runtime_error);  // no frames yet
  EXPECT_THROW(VtkSeriesWriter("/dev/null/out"), std::runtime_error);  // cannot be a directory
  fs::remove_all(dir);
}
