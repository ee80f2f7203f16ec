// rbcflow mesh on the example cases: exit status 0, the printed counts, and WALL.msh / WALL.vtp
// that read back as the checked wall (the command's error paths: CMakeLists.txt beside this).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"
#include "geometry/vessel/vessel.h"
#include "io/vtk_polydata.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

struct Meshed {
  std::string stdout_text;
  fs::path msh, vtp;
};

// Runs `rbcflow mesh CASE -o DIR/NAME.msh` in a fresh directory.
Meshed run_mesh(const std::string& case_name) {
  const fs::path dir = fs::temp_directory_path() / ("rbcflow_test_cmd_mesh_" + case_name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  Meshed m{"", dir / "wall.msh", dir / "wall.vtp"};
  const fs::path log = dir / "stdout.txt";
  const std::string command = std::string("\"") + RBCFLOW_EXE + "\" mesh \"" + RBCFLOW_CASES + "/" + case_name +
                              ".toml\" -o \"" + m.msh.string() + "\" > \"" + log.string() + "\"";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::stringstream text;
  text << std::ifstream(log).rdbuf();
  m.stdout_text = text.str();
  return m;
}

void expect_printed(const Meshed& m, const VesselMesh& wall) {
  const std::string counts = std::to_string(wall.surface.num_points()) + " nodes, " +
                             std::to_string(wall.surface.num_triangles()) + " triangles";
  EXPECT_NE(m.stdout_text.find(counts), std::string::npos) << m.stdout_text;
  EXPECT_NE(m.stdout_text.find("min angle"), std::string::npos) << m.stdout_text;
}

}  // namespace

// data/cases/constriction.toml: D = 3.5, d(z) = 3.5 - 2.2 exp(-1.2 (z - 5)^2), box 5 x 5 x 10.
TEST(MeshCommand, ConstrictionFilesReadBack) {
  const Meshed m = run_mesh("constriction");
  ASSERT_TRUE(fs::is_regular_file(m.msh));
  ASSERT_TRUE(fs::is_regular_file(m.vtp));
  const VesselMesh wall = read_vessel(m.msh.string(), Eigen::Vector3d(0, 0, 10));  // runs check_mesh
  expect_printed(m, wall);
  EXPECT_LT(lumen_flux(wall), 0.0);
  for (int i = 0; i < wall.surface.num_points(); ++i) {
    const Eigen::Vector3d x = wall.surface.points.row(i);
    const double d = 3.5 - 2.2 * std::exp(-1.2 * (x[2] - 5) * (x[2] - 5));
    EXPECT_NEAR(2 * std::hypot(x[0] - 2.5, x[1] - 2.5), d, 1e-5 * 3.5) << x.transpose();  // test_vessel's bound
  }
  const TriangleMesh drawn = read_vtp(m.vtp);
  EXPECT_EQ(drawn.num_triangles(), wall.surface.num_triangles());
  EXPECT_GT(drawn.num_points(), wall.surface.num_points());  // the seam drawn on both faces
}

// data/cases/bifurcation.toml, and its .msh as a `file` vessel gives the same wall.
TEST(MeshCommand, BifurcationFilesReadBack) {
  const Meshed m = run_mesh("bifurcation");
  const VesselMesh wall = read_vessel(m.msh.string(), Eigen::Vector3d(0, 0, 16));
  expect_printed(m, wall);
  EXPECT_LT(lumen_flux(wall), 0.0);
  VesselFileSpec spec;
  spec.path = m.msh.string();
  spec.box = Eigen::Vector3d(12, 6, 16);
  EXPECT_EQ(vessel_file(spec).surface.triangles, wall.surface.triangles);
  EXPECT_EQ(read_vtp(m.vtp).num_triangles(), wall.surface.num_triangles());
}

// data/cases/network.toml: every triangle of the .vtp carries its branch (the segment whose
// centreline is nearest), each of the six segments has triangles, and the triangles about the
// parent's middle (z = 2, well below the split at 4) are all the parent's.
TEST(MeshCommand, NetworkTrianglesCarryTheirBranch) {
  const Meshed m = run_mesh("network");
  EXPECT_NE(m.stdout_text.find("branches: 6"), std::string::npos) << m.stdout_text;
  const TriangleMesh drawn = read_vtp(m.vtp);
  const Eigen::MatrixXd branch = read_vtp_triangle_field(m.vtp, "branch");
  ASSERT_EQ(branch.rows(), drawn.num_triangles());
  std::vector<int> count(6, 0);
  for (int t = 0; t < drawn.num_triangles(); ++t) {
    const int b = static_cast<int>(branch(t, 0));
    ASSERT_GE(b, 0);
    ASSERT_LT(b, 6);
    ++count[b];
    double z = 0;
    for (int a = 0; a < 3; ++a) z += drawn.points(drawn.triangles(t, a), 2) / 3;
    if (std::abs(z - 2.0) < 1.0) {
      EXPECT_EQ(b, 0) << "triangle " << t << " at z = " << z;
    }
  }
  for (int b = 0; b < 6; ++b) EXPECT_GT(count[b], 100) << "branch " << b;
  EXPECT_THROW(read_vtp_triangle_field(m.vtp, "cell"), std::runtime_error);
}
