// XDMF 3 + HDF5 series: read back with the HDF5 C API and VTK's XML parser; every DataItem of
// the XML must name an existing dataset of the stated dimensions. A killed writer leaves a
// readable series; a restart drops the frames after its step.
#include "io/xdmf_writer.h"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <csignal>
#include <fstream>
#include <sstream>

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

// Two cells that move with time, and a fixed wall.
std::vector<Surface> frame(double t) {
  const SHTransform tr = SHTransform::gauss(6);
  std::vector<Surface> cells;
  for (int k = 0; k < 2; ++k) {
    SHSurface s = make_sphere(6);
    s.translate(Eigen::Vector3d(3.0 * k, 0, t));
    Surface c{"cell", s.triangulate(tr), {}};
    const int n = c.mesh.num_points();
    c.fields.push_back({"velocity", Eigen::MatrixXd::Constant(n, 3, t)});
    c.fields.push_back({"tension", Eigen::MatrixXd::Constant(n, 1, k + t)});
    cells.push_back(std::move(c));
  }
  Surface wall{"wall", make_sphere(6, 8.0).triangulate(tr), {}};
  wall.fields.push_back({"traction", Eigen::MatrixXd::Constant(wall.mesh.num_points(), 3, -t)});
  return {merge_surfaces("cells", cells), wall};
}

std::vector<hsize_t> dataset_shape(hid_t file, const std::string& path) {
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (set < 0) return {};
  const hid_t space = H5Dget_space(set);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(set);
  return dims;
}

Eigen::MatrixXd read_points(hid_t file, const std::string& path) {
  const auto dims = dataset_shape(file, path);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(dims[0], dims[1]);
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data());
  H5Dclose(set);
  return m;
}

int count_children(vtkXMLDataElement* e, const char* name) {
  int n = 0;
  for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) n += std::string(e->GetNestedElement(i)->GetName()) == name;
  return n;
}

// Checks every DataItem of the .xdmf against the .h5 beside it; returns the number of frames.
int check_series(const fs::path& xdmf) {
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromFile(xdmf.c_str()));
  EXPECT_TRUE(root);
  if (!root) return -1;
  EXPECT_STREQ(root->GetName(), "Xdmf");
  EXPECT_STREQ(root->GetAttribute("Version"), "3.0");
  vtkXMLDataElement* temporal = root->FindNestedElementWithName("Domain")->FindNestedElementWithName("Grid");
  EXPECT_STREQ(temporal->GetAttribute("CollectionType"), "Temporal");
  const hid_t file = H5Fopen((xdmf.parent_path() / "rbcflow.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(file, 0);
  double last_time = -1;
  for (int f = 0; f < temporal->GetNumberOfNestedElements(); ++f) {
    vtkXMLDataElement* spatial = temporal->GetNestedElement(f);
    EXPECT_STREQ(spatial->GetAttribute("CollectionType"), "Spatial");
    const double time = std::stod(spatial->FindNestedElementWithName("Time")->GetAttribute("Value"));
    EXPECT_GT(time, last_time);
    last_time = time;
    EXPECT_EQ(count_children(spatial, "Grid"), 2);
    for (int g = 0; g < spatial->GetNumberOfNestedElements(); ++g) {
      vtkXMLDataElement* grid = spatial->GetNestedElement(g);
      if (std::string(grid->GetName()) != "Grid") continue;
      EXPECT_EQ(count_children(grid, "Topology"), 1);
      EXPECT_EQ(count_children(grid, "Geometry"), 1);
      for (int c = 0; c < grid->GetNumberOfNestedElements(); ++c) {
        vtkXMLDataElement* item = grid->GetNestedElement(c)->FindNestedElementWithName("DataItem");
        if (!item) continue;
        const std::string text = item->GetCharacterData();
        EXPECT_EQ(text.rfind("rbcflow.h5:/frames/", 0), 0u) << text;  // relative to the .xdmf
        const auto dims = dataset_shape(file, text.substr(text.find(':') + 1));
        std::ostringstream expected;
        for (std::size_t d = 0; d < dims.size(); ++d) expected << (d ? " " : "") << dims[d];
        EXPECT_EQ(expected.str(), item->GetAttribute("Dimensions")) << text;
      }
    }
  }
  H5Fclose(file);
  return temporal->GetNumberOfNestedElements();
}

}  // namespace

TEST(XdmfWriter, FramesReadBackWithHdf5AndTheXmlMatchesThem) {
  const fs::path dir = fresh_dir("rbcflow_test_xdmf");
  {
    XdmfWriter w(dir);
    for (int k = 0; k < 3; ++k) w.write_frame(100 * k, 0.5 * k, frame(0.5 * k));
    EXPECT_EQ(w.frames(), 3);
    // Between frames the series reads while the writer lives (ParaView watching a run).
    EXPECT_EQ(check_series(dir / "rbcflow.xdmf"), 3);
    w.write_frame(300, 1.5, frame(1.5));
  }
  EXPECT_EQ(check_series(dir / "rbcflow.xdmf"), 4);
  const hid_t file = H5Fopen((dir / "rbcflow.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const std::vector<Surface> third = frame(1.0);
  const Eigen::MatrixXd points = read_points(file, "/frames/00000200/cells/points");
  EXPECT_EQ((points - Eigen::MatrixXd(third[0].mesh.points)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(dataset_shape(file, "/frames/00000200/cells/tension"), std::vector<hsize_t>{hsize_t(points.rows())});
  EXPECT_EQ(dataset_shape(file, "/frames/00000200/cells/velocity"), (std::vector<hsize_t>{hsize_t(points.rows()), 3}));
  // The fixed wall is stored once: later frames link to it; the moving cells are not linked.
  H5L_info_t info;
  ASSERT_GE(H5Lget_info(file, "/frames/00000200/wall/points", &info, H5P_DEFAULT), 0);
  EXPECT_EQ(info.type, H5L_TYPE_SOFT);
  ASSERT_GE(H5Lget_info(file, "/frames/00000200/cells/points", &info, H5P_DEFAULT), 0);
  EXPECT_EQ(info.type, H5L_TYPE_HARD);
  ASSERT_GE(H5Lget_info(file, "/frames/00000200/cells/triangles", &info, H5P_DEFAULT), 0);
  EXPECT_EQ(info.type, H5L_TYPE_SOFT);
  const hid_t g = H5Gopen2(file, "/frames/00000100", H5P_DEFAULT);
  const hid_t a = H5Aopen(g, "time", H5P_DEFAULT);
  double time = 0;
  H5Aread(a, H5T_NATIVE_DOUBLE, &time);
  EXPECT_EQ(time, 0.5);
  H5Aclose(a);
  H5Gclose(g);
  H5Fclose(file);
  fs::remove_all(dir);
}

TEST(XdmfWriter, KilledWriterLeavesAReadableSeries) {
  const fs::path dir = fresh_dir("rbcflow_test_xdmf_kill");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    XdmfWriter w(dir);
    w.write_frame(0, 0.0, frame(0.0));
    w.write_frame(1, 0.1, frame(0.1));
    std::raise(SIGKILL);  // no destructor, no close: as if the machine killed the run
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(check_series(dir / "rbcflow.xdmf"), 2);
  // And a restart continues it.
  XdmfWriter w(dir, 1);
  w.write_frame(2, 0.2, frame(0.2));
  EXPECT_EQ(check_series(dir / "rbcflow.xdmf"), 3);
  fs::remove_all(dir);
}

TEST(XdmfWriter, RestartDropsFramesAfterItsStep) {
  const fs::path dir = fresh_dir("rbcflow_test_xdmf_restart");
  {
    XdmfWriter w(dir);
    for (long s : {0, 10, 20, 30}) w.write_frame(s, 0.01 * s, frame(0.01 * s));
  }
  {
    XdmfWriter w(dir, 20);
    EXPECT_EQ(w.frames(), 3);
    EXPECT_THROW(w.write_frame(20, 0.2, frame(0.2)), std::invalid_argument);  // steps increase
    w.write_frame(25, 0.25, frame(0.25));
  }
  EXPECT_EQ(check_series(dir / "rbcflow.xdmf"), 4);
  const hid_t file = H5Fopen((dir / "rbcflow.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_EQ(H5Lexists(file, "/frames/00000030", H5P_DEFAULT), 0);
  EXPECT_GT(H5Lexists(file, "/frames/00000025", H5P_DEFAULT), 0);
  H5Fclose(file);
  fs::remove_all(dir);
}

TEST(XdmfWriter, BadInputIsAClearError) {
  const fs::path dir = fresh_dir("rbcflow_test_xdmf_bad");
  XdmfWriter w(dir);
  std::vector<Surface> f = frame(0);
  f[1].fields[0].values.resize(3, 3);
  EXPECT_THROW(w.write_frame(0, 0, f), std::invalid_argument);
  f = frame(0);
  f[0].fields[0].name = "bad name";
  EXPECT_THROW(w.write_frame(0, 0, f), std::invalid_argument);
  f[0].fields[0].name = "points";
  EXPECT_THROW(w.write_frame(0, 0, f), std::invalid_argument);
  EXPECT_EQ(w.frames(), 0);
  try {
    XdmfWriter none("/nonexistent-dir");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/rbcflow.h5"), std::string::npos) << e.what();
  }
  // A foreign file where the series should continue.
  const fs::path other = fresh_dir("rbcflow_test_xdmf_foreign");
  std::ofstream(other / "rbcflow.h5") << "not HDF5";
  try {
    XdmfWriter resumed(other, 5);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot continue the XDMF series"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
  fs::remove_all(other);
}
