#include "io/plot.h"

#include <vtkAxis.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/csv.h"
#include "io/render.h"
#include "io/vtk_internal.h"

namespace rbcflow {

namespace fs = std::filesystem;

namespace {

struct Series {
  std::string name;
  std::vector<double> t, y;
};

// The rows of `column` that have a value, against time.
Series series(const CsvTable& table, const std::string& column, const std::string& name) {
  const std::size_t time = table.column("time"), c = table.column(column);
  Series s{name, {}, {}};
  for (const auto& row : table.rows) {
    if (row[c].empty()) continue;
    s.t.push_back(std::strtod(row[time].c_str(), nullptr));
    s.y.push_back(std::strtod(row[c].c_str(), nullptr));
  }
  return s;
}

void add_line(vtkChartXY* chart, const Series& s, const unsigned char rgb[3]) {
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> t, y;
  t->SetName("time");
  y->SetName(s.name.c_str());
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    t->InsertNextValue(s.t[i]);
    y->InsertNextValue(s.y[i]);
  }
  table->AddColumn(t);
  table->AddColumn(y);
  // A one-step run has one row: a line needs two points (VTK logs an error), so draw a point.
  vtkPlot* line = chart->AddPlot(s.t.size() < 2 ? vtkChart::POINTS : vtkChart::LINE);
  line->SetInputData(table, 0, 1);
  line->SetColor(rgb[0], rgb[1], rgb[2], 255);
  line->SetWidth(2.0);
}

void style(vtkChartXY* chart, const std::string& title, const std::string& y_title) {
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("time (1/k*)");
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(y_title);
  chart->SetShowLegend(true);
}

}  // namespace

void plot_diagnostics(const fs::path& csv, const fs::path& png, int width, int height) {
  if (!display_available()) {
    throw std::runtime_error("cannot plot " + png.string() + ": no X display (see docs/rendering.md)");
  }
  const CsvTable table = read_csv(csv);
  if (table.rows.empty()) throw std::runtime_error("cannot plot " + csv.string() + ": no rows yet");

  const Series viscosity = series(table, "effective_viscosity", "effective viscosity (46)");
  std::vector<Series> gradient;  // the components that are not all zero (z if none is)
  for (const char axis : {'x', 'y', 'z'}) {
    Series s = series(table, std::string("pressure_gradient_") + axis, std::string("<grad p>_") + axis);
    for (const double v : s.y) {
      if (v != 0.0) {
        gradient.push_back(std::move(s));
        break;
      }
    }
  }
  if (gradient.empty()) gradient.push_back(series(table, "pressure_gradient_z", "<grad p>_z"));

  vtkNew<vtkContextView> view;
  view->GetRenderer()->SetBackground(1, 1, 1);
  // No interactor: a picture needs no events, and the interactor's own X connection crashed
  // (XSync on a failed XOpenDisplay) when several processes rendered on one Xvfb.
  view->SetInteractor(nullptr);
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(width, height);
  vtkNew<vtkChartMatrix> matrix;
  const bool with_viscosity = !viscosity.t.empty();
  matrix->SetSize(vtkVector2i(1, with_viscosity ? 2 : 1));
  matrix->SetGutter(vtkVector2f(30.0f, 90.0f));  // room for the lower chart's title
  view->GetScene()->AddItem(matrix);

  static const unsigned char colours[3][3] = {{31, 119, 180}, {214, 39, 40}, {44, 160, 44}};
  auto* bottom = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 0)));
  style(bottom, "Mean pressure gradient", "<grad p>");
  for (std::size_t i = 0; i < gradient.size(); ++i) add_line(bottom, gradient[i], colours[(i + 1) % 3]);
  if (with_viscosity) {
    auto* top = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 1)));
    style(top, "Effective viscosity", "mu_eff / mu");
    add_line(top, viscosity, colours[0]);
  }
  write_png(view->GetRenderWindow(), png);
}

}  // namespace rbcflow
