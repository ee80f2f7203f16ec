// The run's plot from diagnostics.csv (run under xvfb-run, as scripts/test.sh does).
#include "io/plot.h"

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cmath>
#include <set>

#include "io/csv.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

// Width, height and the number of distinct colours of a PNG.
std::array<int, 3> inspect(const fs::path& png) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  std::set<long> colours;
  for (int y = 0; y < dims[1]; ++y) {
    for (int x = 0; x < dims[0]; ++x) {
      const auto* p = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
      colours.insert(p[0] * 65536L + p[1] * 256L + p[2]);
    }
  }
  return {dims[0], dims[1], static_cast<int>(colours.size())};
}

void write_diagnostics(const fs::path& csv, bool tube) {
  DiagnosticsCsv d(csv);
  for (long s = 0; s < 50; ++s) {
    DiagnosticsRow r;
    r.step = s;
    r.time = 0.01 * s;
    r.pressure_gradient = {0, 0, -2 - std::exp(-0.1 * s)};
    if (tube) r.effective_viscosity = 1.5 + 0.3 * std::exp(-0.1 * s);
    d.write(r);
  }
}

}  // namespace

TEST(Plot, ViscosityAndPressureGradientAgainstTime) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_plot";
  fs::create_directories(dir);
  write_diagnostics(dir / "diagnostics.csv", true);
  plot_diagnostics(dir / "diagnostics.csv", dir / "plot.png", 800, 600);
  const auto with_tube = inspect(dir / "plot.png");
  EXPECT_EQ(with_tube[0], 800);
  EXPECT_EQ(with_tube[1], 600);
  EXPECT_GT(with_tube[2], 20);  // text, axes and coloured lines on white (antialiased)
  // Without a tube: the pressure gradient alone.
  write_diagnostics(dir / "free.csv", false);
  plot_diagnostics(dir / "free.csv", dir / "free.png", 400, 300);
  EXPECT_EQ(inspect(dir / "free.png")[0], 400);
  fs::remove_all(dir);
}

TEST(Plot, MissingOrEmptyDiagnosticsAreClearErrors) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_plot_bad";
  fs::create_directories(dir);
  EXPECT_THROW(plot_diagnostics(dir / "none.csv", dir / "x.png"), std::runtime_error);
  { DiagnosticsCsv empty(dir / "empty.csv"); }
  try {
    plot_diagnostics(dir / "empty.csv", dir / "x.png");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no rows yet"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(dir / "x.png"));
  fs::remove_all(dir);
}
