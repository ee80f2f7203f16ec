#pragma once
// Off-screen PNG renders of a frame with VTK: cells coloured by a point field (its magnitude
// for vectors) with a colour bar, the wall translucent grey.
//
// Debian's VTK renders only through X (no OSMesa/EGL): without a display VTK aborts the
// process, so render_png refuses to start when DISPLAY is unset. `rbcflow render` starts a
// virtual display (Xvfb) itself; see docs/rendering.md.
#include <filesystem>
#include <string>
#include <vector>

#include "io/case.h"
#include "io/surface.h"

namespace rbcflow {

struct RenderOptions {
  std::string field = "tension";  // point field of the cells; "none" for one colour
  RenderView view = RenderView::iso;
  int width = 1280;
  int height = 720;
  int axis = 2;        // the flow / vessel axis: side views look across it, end views along it
  std::string label;   // written in the top-left corner (e.g. "step 100   t = 0.5")
  // > 0: the box side along `axis` of a periodic domain; each cell (by its "cell" field) is
  // drawn shifted by whole periods so that its centroid lies in [0, period), inside the
  // drawn vessel, however far it has travelled.
  double period = 0;
};

// The mesh of a cells surface (merge_surfaces' "cell" field) with each cell shifted by whole
// periods along `axis` so that its centroid (the mean of its points) lies in [0, period);
// unchanged without that field or for period <= 0. What render_png draws for the cells.
TriangleMesh cells_in_period(const Surface& cells, int axis, double period);

// Surfaces named "wall" are drawn translucent; all others are cells. Writes `png`
// atomically. Throws InputError when no cell surface has `field` (the message lists the
// fields there are); std::runtime_error when there is no display or the PNG cannot be written.
void render_png(const std::vector<Surface>& surfaces, const RenderOptions& options,
                const std::filesystem::path& png);

// True when an X display is set (DISPLAY), which Debian's VTK needs to render.
bool display_available();

}  // namespace rbcflow
