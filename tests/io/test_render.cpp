// Off-screen renders (run under xvfb-run, as scripts/test.sh does): the PNG has the asked size
// and a picture in it, every view works, and bad requests are clear errors.
#include "io/render.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <set>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

// A tube of diameter d along z, length l, as a triangle mesh (open ends).
TriangleMesh tube(double d, double l, int around = 32, int along = 20) {
  TriangleMesh m;
  m.points.resize(around * (along + 1), 3);
  for (int k = 0; k <= along; ++k) {
    for (int j = 0; j < around; ++j) {
      const double phi = 2 * std::numbers::pi * j / around;
      m.points.row(k * around + j) << d / 2 * std::cos(phi), d / 2 * std::sin(phi), l * k / along;
    }
  }
  m.triangles.resize(2 * around * along, 3);
  for (int k = 0; k < along; ++k) {
    for (int j = 0; j < around; ++j) {
      const int a = k * around + j, b = k * around + (j + 1) % around;
      m.triangles.row(2 * (k * around + j)) << a, b, b + around;
      m.triangles.row(2 * (k * around + j) + 1) << a, b + around, a + around;
    }
  }
  return m;
}

std::vector<Surface> scene() {
  const SHTransform t = SHTransform::gauss(12);
  std::vector<Surface> cells;
  for (int k = 0; k < 2; ++k) {
    SHSurface s = make_biconcave(12);
    s.rotate(Eigen::AngleAxisd(0.4 * k, Eigen::Vector3d::UnitX()).toRotationMatrix());
    s.translate(Eigen::Vector3d(0.3 * k, 0, 2.5 + 3 * k));
    Surface c{"cell", s.triangulate(t), {}};
    c.fields.push_back({"tension", c.mesh.points.col(2).array().sin().matrix()});
    c.fields.push_back({"velocity", Eigen::MatrixXd(c.mesh.points)});
    cells.push_back(std::move(c));
  }
  Surface wall{"wall", tube(4, 8), {}};
  wall.fields.push_back({"traction", Eigen::MatrixXd::Ones(wall.mesh.num_points(), 3)});
  return {merge_surfaces("cells", cells), wall};
}

struct Picture {
  int width = 0, height = 0;
  int colours = 0;
};

Picture read_png(const fs::path& png) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  std::set<long> colours;
  const int components = image->GetNumberOfScalarComponents();
  for (int y = 0; y < dims[1]; y += 2) {
    for (int x = 0; x < dims[0]; x += 2) {
      const auto* p = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
      colours.insert(p[0] * 65536L + p[1] * 256L + p[2 % components]);
    }
  }
  return {dims[0], dims[1], static_cast<int>(colours.size())};
}

}  // namespace

TEST(Render, EveryViewGivesAPictureOfTheAskedSize) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_render";
  fs::create_directories(dir);
  const std::vector<Surface> s = scene();
  for (const RenderView view : {RenderView::side, RenderView::end, RenderView::iso}) {
    RenderOptions o;
    o.view = view;
    o.width = 640;
    o.height = 400;
    o.label = "step 100   t = 0.5";
    const fs::path png = dir / ("cells_" + to_string(view) + ".png");
    render_png(s, o, png);
    const Picture p = read_png(png);
    EXPECT_EQ(p.width, 640);
    EXPECT_EQ(p.height, 400);
    // Background gradient, shaded coloured cells, translucent wall, colour bar, text:
    // hundreds of colours. A blank or single-colour image has a handful.
    EXPECT_GT(p.colours, 200) << to_string(view);
  }
  fs::remove_all(dir);
}

TEST(Render, VectorFieldsAndNoFieldAlsoRender) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_render_fields";
  fs::create_directories(dir);
  RenderOptions o;
  o.width = 320;
  o.height = 240;
  o.field = "velocity";  // coloured by its magnitude
  render_png(scene(), o, dir / "velocity.png");
  EXPECT_GT(read_png(dir / "velocity.png").colours, 100);
  o.field = "none";
  render_png(scene(), o, dir / "plain.png");
  const Picture plain = read_png(dir / "plain.png");
  EXPECT_EQ(plain.width, 320);
  EXPECT_GT(plain.colours, 50);
  fs::remove_all(dir);
}

TEST(Render, BadRequestsAreClearErrors) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_render_bad";
  fs::create_directories(dir);
  RenderOptions o;
  o.field = "pressure";
  try {
    render_png(scene(), o, dir / "x.png");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no field 'pressure' (fields: tension, velocity, cell)"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "x.png"));
  o.field = "tension";
  o.width = 4;
  EXPECT_THROW(render_png(scene(), o, dir / "x.png"), std::invalid_argument);
  o.width = 100;
  EXPECT_THROW(render_png(scene(), o, "/nonexistent-dir/x.png"), std::runtime_error);
  // Without a display VTK would abort the process: render_png refuses first.
  const std::string display = std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "";
  unsetenv("DISPLAY");
  EXPECT_FALSE(display_available());
  EXPECT_THROW(render_png(scene(), o, dir / "x.png"), std::runtime_error);
  setenv("DISPLAY", display.c_str(), 1);
  fs::remove_all(dir);
}

// Periodic runs: cells that travelled 2 and -1 periods (centroid means 2.5 + 16 and 5.5 - 8)
// are drawn back in [0, 8), each shifted by whole periods only, its shape unchanged; the
// wall and a free domain (period 0) are left alone.
TEST(Render, CellsAreDrawnWrappedIntoThePeriod) {
  std::vector<Surface> s = scene();
  Surface& cells = s[0];
  const Eigen::VectorXd id = cells.fields.back().values.col(0);
  ASSERT_EQ(cells.fields.back().name, "cell");
  TriangleMesh moved = cells.mesh;
  for (Eigen::Index p = 0; p < id.size(); ++p) moved.points(p, 2) += id[p] < 0.5 ? 16.0 : -8.0;
  cells.mesh = moved;
  const TriangleMesh wrapped = cells_in_period(cells, 2, 8.0);
  for (int k = 0; k < 2; ++k) {
    double sum = 0;
    int n = 0;
    for (Eigen::Index p = 0; p < id.size(); ++p) {
      if (std::lround(id[p]) != k) continue;
      const double shift = wrapped.points(p, 2) - moved.points(p, 2);
      EXPECT_NEAR(shift, k == 0 ? -16.0 : 8.0, 1e-12);
      EXPECT_EQ(wrapped.points(p, 0), moved.points(p, 0));
      sum += wrapped.points(p, 2);
      ++n;
    }
    EXPECT_NEAR(sum / n, k == 0 ? 2.5 : 5.5, 1e-2);  // the reference cell's point mean is ~ its centroid
  }
  EXPECT_EQ(cells_in_period(cells, 2, 0.0).points, moved.points);
  EXPECT_EQ(cells_in_period(s[1], 2, 8.0).points, s[1].mesh.points);  // the wall has no "cell" field
}
