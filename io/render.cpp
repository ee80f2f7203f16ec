#include "io/render.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDoubleArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/input_error.h"
#include "io/vtk_internal.h"

namespace rbcflow {

namespace fs = std::filesystem;

namespace {

// The values coloured: the field itself, or the magnitude of each row.
Eigen::VectorXd colour_values(const SurfaceField& f) {
  return f.values.cols() == 1 ? Eigen::VectorXd(f.values.col(0)) : Eigen::VectorXd(f.values.rowwise().norm());
}

const SurfaceField* find_field(const Surface& s, const std::string& name) {
  for (const SurfaceField& f : s.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

// Smooth shading: point normals of the triangulated surface.
vtkSmartPointer<vtkPolyDataMapper> mapper_for(vtkPolyData* poly) {
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(poly);
  normals->SplittingOff();
  normals->ConsistencyOn();
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(normals->GetOutputPort());
  return mapper;
}

void place_camera(vtkRenderer* renderer, const RenderOptions& o) {
  const int a = o.axis, b = (a + 1) % 3, c = (a + 2) % 3;
  double up[3] = {0, 0, 0}, view[3] = {0, 0, 0};
  up[b] = 1;
  vtkCamera* camera = renderer->GetActiveCamera();
  if (o.view == RenderView::end) {
    view[a] = 1;  // the flow comes toward the viewer
  } else {
    view[c] = 1;  // side: the flow runs from left to right
  }
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(view);
  camera->SetViewUp(up);
  if (o.view == RenderView::iso) {
    camera->Azimuth(-35);
    camera->Elevation(30);
    camera->OrthogonalizeViewUp();
  } else if (o.view == RenderView::side) {
    camera->ParallelProjectionOn();  // as in a drawing; the end view keeps perspective to show the wall
  }
  renderer->ResetCamera();
  camera->Zoom(1.15);
}

}  // namespace

bool display_available() {
  const char* display = std::getenv("DISPLAY");
  return display && *display;
}

TriangleMesh cells_in_period(const Surface& s, int axis, double period) {
  TriangleMesh m = s.mesh;
  const SurfaceField* id = find_field(s, "cell");
  if (!id || period <= 0) return m;
  std::map<long, std::pair<double, int>> sums;  // cell -> (sum of coordinates, points)
  for (Eigen::Index p = 0; p < m.points.rows(); ++p) {
    auto& [sum, count] = sums[std::lround(id->values(p, 0))];
    sum += m.points(p, axis);
    ++count;
  }
  for (Eigen::Index p = 0; p < m.points.rows(); ++p) {
    const auto& [sum, count] = sums[std::lround(id->values(p, 0))];
    m.points(p, axis) -= period * std::floor(sum / count / period);
  }
  return m;
}

void render_png(const std::vector<Surface>& surfaces, const RenderOptions& o, const fs::path& png) {
  if (!display_available()) {
    throw std::runtime_error("cannot render " + png.string() +
                             ": no X display (DISPLAY is unset). Debian's VTK renders only through X: "
                             "run under xvfb-run, or use 'rbcflow render', which starts Xvfb itself");
  }
  if (o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192) {
    throw std::invalid_argument("render size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                                " is outside 16..8192");
  }
  // The colour range over all cells.
  const bool coloured = o.field != "none";
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::vector<std::string> available;
  bool found = false;
  for (const Surface& s : surfaces) {
    if (s.name == "wall") continue;
    for (const SurfaceField& f : s.fields) {
      if (std::find(available.begin(), available.end(), f.name) == available.end()) available.push_back(f.name);
    }
    if (const SurfaceField* f = coloured ? find_field(s, o.field) : nullptr) {
      const Eigen::VectorXd v = colour_values(*f);
      if (v.size() > 0) {
        lo = std::min(lo, v.minCoeff());
        hi = std::max(hi, v.maxCoeff());
      }
      found = true;
    }
  }
  if (coloured && !found) {
    std::string names;
    for (const std::string& n : available) names.append(names.empty() ? "" : ", ").append(n);
    throw InputError("cannot render " + png.string() + ": the cells have no field '" + o.field +
                     "' (fields: " + (names.empty() ? "none" : names) + ")");
  }
  if (!coloured) lo = 0, hi = 1;
  if (!(hi > lo)) hi = lo + 1;  // a uniform field still gets a colour bar

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  renderer->SetBackground2(0.82, 0.85, 0.9);
  renderer->GradientBackgroundOn();
  renderer->SetUseDepthPeeling(1);
  renderer->SetMaximumNumberOfPeels(8);

  vtkNew<vtkLookupTable> table;
  table->SetHueRange(0.667, 0.0);  // blue (low) to red (high)
  table->SetTableRange(lo, hi);
  table->Build();

  for (const Surface& s : surfaces) {
    validate(s);
    const vtkSmartPointer<vtkPolyData> poly =
        to_polydata(s.name == "wall" ? s.mesh : cells_in_period(s, o.axis, o.period), {});
    vtkNew<vtkActor> actor;
    if (s.name == "wall") {
      actor->SetMapper(mapper_for(poly));
      actor->GetProperty()->SetColor(0.6, 0.6, 0.65);
      actor->GetProperty()->SetOpacity(0.25);
    } else {
      const SurfaceField* f = coloured ? find_field(s, o.field) : nullptr;
      if (f) {
        const Eigen::VectorXd v = colour_values(*f);
        vtkNew<vtkDoubleArray> scalars;
        scalars->SetName(o.field.c_str());
        scalars->SetNumberOfTuples(v.size());
        for (Eigen::Index p = 0; p < v.size(); ++p) scalars->SetValue(p, v[p]);
        poly->GetPointData()->SetScalars(scalars);
      }
      const vtkSmartPointer<vtkPolyDataMapper> mapper = mapper_for(poly);
      if (f) {
        mapper->SetLookupTable(table);
        mapper->SetScalarRange(lo, hi);
        mapper->ScalarVisibilityOn();
      } else {
        mapper->ScalarVisibilityOff();
        actor->GetProperty()->SetColor(0.8, 0.15, 0.15);
      }
      actor->SetMapper(mapper);
      actor->GetProperty()->SetSpecular(0.3);
      actor->GetProperty()->SetSpecularPower(20);
    }
    renderer->AddActor(actor);
  }
  if (coloured) {
    vtkNew<vtkScalarBarActor> bar;
    bar->SetLookupTable(table);
    bar->SetTitle(o.field.c_str());
    bar->SetNumberOfLabels(5);
    bar->SetMaximumWidthInPixels(std::max(60, o.width / 12));
    bar->GetTitleTextProperty()->SetColor(0.1, 0.1, 0.1);
    bar->GetLabelTextProperty()->SetColor(0.1, 0.1, 0.1);
    bar->GetTitleTextProperty()->ShadowOff();
    bar->GetLabelTextProperty()->ShadowOff();
    renderer->AddActor2D(bar);
  }
  if (!o.label.empty()) {
    vtkNew<vtkTextActor> text;
    text->SetInput(o.label.c_str());
    text->GetTextProperty()->SetFontSize(std::max(12, o.height / 30));
    text->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
    text->SetDisplayPosition(10, o.height - 10 - std::max(12, o.height / 30));
    renderer->AddActor2D(text);
  }
  place_camera(renderer, o);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetAlphaBitPlanes(1);
  window->SetMultiSamples(0);
  window->SetSize(o.width, o.height);
  window->AddRenderer(renderer);
  write_png(window, png);
}

void write_png(vtkRenderWindow* window, const fs::path& png) {
  window->Render();
  vtkNew<vtkWindowToImageFilter> image;
  image->SetInput(window);
  image->ReadFrontBufferOff();
  image->Update();
  write_atomically(png, [&](const fs::path& tmp) {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputConnection(image->GetOutputPort());
    writer->Write();
    if (!fs::exists(tmp) || fs::file_size(tmp) == 0) throw std::runtime_error("cannot write " + png.string());
  });
}

}  // namespace rbcflow
