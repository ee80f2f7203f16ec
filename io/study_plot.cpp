#include "io/study_plot.h"

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "io/render.h"
#include "io/vtk_internal.h"

namespace rbcflow {

namespace {

vtkPlot* add(vtkChartXY* chart, int type, const std::string& name, const std::vector<double>& x,
             const std::vector<double>& y, const unsigned char rgb[3], float width) {
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> xs, ys;
  xs->SetName("D");
  ys->SetName(name.c_str());
  for (std::size_t i = 0; i < x.size(); ++i) {
    xs->InsertNextValue(x[i]);
    ys->InsertNextValue(y[i]);
  }
  table->AddColumn(xs);
  table->AddColumn(ys);
  vtkPlot* p = chart->AddPlot(type);
  p->SetInputData(table, 0, 1);
  p->SetColor(rgb[0], rgb[1], rgb[2], 255);
  p->SetWidth(width);
  return p;
}

const unsigned char kPalette[6][3] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},
                                      {214, 39, 40},  {148, 103, 189}, {140, 86, 75}};

// An off-screen chart view of the given size on a white background.
vtkNew<vtkContextView> chart_view(const std::filesystem::path& png, int width, int height) {
  if (!display_available()) {
    throw std::runtime_error("cannot plot " + png.string() + ": no X display (see docs/rendering.md)");
  }
  vtkNew<vtkContextView> view;
  view->GetRenderer()->SetBackground(1, 1, 1);
  // No interactor: a picture needs no events, and the interactor's own X connection crashed
  // (XSync on a failed XOpenDisplay) when several processes rendered on one Xvfb.
  view->SetInteractor(nullptr);
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(width, height);
  return view;
}

// A chart with a legend in `view`, titled, its axes named.
vtkChartXY* add_chart(vtkContextView* view, const std::string& title, const std::string& x, const std::string& y) {
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(x);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(y);
  chart->SetShowLegend(true);
  return chart;  // the scene holds it
}

}  // namespace

void plot_curves(const CurvesPlot& c, const std::filesystem::path& png, int width, int height) {
  vtkNew<vtkContextView> view = chart_view(png, width, height);
  vtkChartXY* chart = add_chart(view, c.title, c.x_title, c.y_title);
  for (std::size_t k = 0; k < c.names.size(); ++k) add(chart, vtkChart::LINE, c.names[k], c.x[k], c.y[k], kPalette[k % 6], 2.0f);
  write_png(view->GetRenderWindow(), png);
}

void plot_study(const StudyPlot& s, const std::filesystem::path& png, int width, int height) {
  vtkNew<vtkContextView> view = chart_view(png, width, height);
  vtkChartXY* chart = add_chart(view, s.title, s.x_title, s.y_title);
  static const unsigned char grey[3] = {150, 150, 150}, black[3] = {40, 40, 40}, blue[3] = {31, 119, 180};
  if (!s.reference_diameter.empty()) {
    add(chart, vtkChart::LINE, s.reference_name, s.reference_diameter, s.reference, black, 2.0f);
    if (!s.reference_low.empty()) {
      add(chart, vtkChart::LINE, s.reference_name + " -10%", s.reference_diameter, s.reference_low, grey, 1.0f);
      add(chart, vtkChart::LINE, s.reference_name + " +10%", s.reference_diameter, s.reference_high, grey, 1.0f);
    }
  }
  // The points are blue (the palette's first colour): the further curves take the others.
  for (std::size_t k = 0; k < s.reference_curves.size(); ++k) {
    const StudyPlot::Curve& c = s.reference_curves[k];
    add(chart, vtkChart::LINE, c.name, c.x, c.y, kPalette[1 + k % 5], 1.5f);
  }
  // Error bars as short vertical lines, then the points.
  for (std::size_t i = 0; i < s.diameter.size(); ++i) {
    if (!(s.bar_high[i] > s.bar_low[i])) continue;
    vtkPlot* bar = add(chart, vtkChart::LINE, "", {s.diameter[i], s.diameter[i]}, {s.bar_low[i], s.bar_high[i]}, blue, 2.0f);
    bar->SetLegendVisibility(false);
  }
  if (!s.reference_at_points.empty()) {
    vtkPlot* crosses = add(chart, vtkChart::POINTS, s.reference_at_points_name, s.diameter, s.reference_at_points, black, 2.0f);
    if (auto* p = vtkPlotPoints::SafeDownCast(crosses)) p->SetMarkerStyle(vtkPlotPoints::CROSS);
  }
  vtkPlot* points = add(chart, vtkChart::POINTS, "simulation", s.diameter, s.value, blue, 3.0f);
  // Headroom above the data and the band for the legend (top right), so that it hides no point.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < s.diameter.size(); ++i) {
    lo = std::min({lo, s.value[i], s.bar_low[i]});
    hi = std::max({hi, s.value[i], s.bar_high[i]});
  }
  for (double v : s.reference_at_points) lo = std::min(lo, v), hi = std::max(hi, v);
  for (double v : s.reference) lo = std::min(lo, v), hi = std::max(hi, v);
  for (const StudyPlot::Curve& c : s.reference_curves) {
    for (double v : c.y) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  for (double v : s.reference_low) lo = std::min(lo, v);
  for (double v : s.reference_high) hi = std::max(hi, v);
  if (lo < hi) {
    const double span = hi - lo;
    chart->GetAxis(vtkAxis::LEFT)->SetBehavior(vtkAxis::FIXED);
    chart->GetAxis(vtkAxis::LEFT)->SetRange(lo - 0.05 * span, hi + 0.35 * span);
  }
  if (auto* p = vtkPlotPoints::SafeDownCast(points)) p->SetMarkerStyle(vtkPlotPoints::CIRCLE);
  write_png(view->GetRenderWindow(), png);
}

}  // namespace rbcflow
