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
};

// Surfaces named "wall" are drawn translucent; all others are cells. Writes `png`
// atomically. Throws InputError when no cell surface has `field` (the message lists the
// fields there are); std::runtime_error when there is no display or the PNG cannot be written.
void render_png(const std::vector<Surface>& surfaces, const RenderOptions& options,
                const std::filesystem::path& png);

// True when an X display is set (DISPLAY), which Debian's VTK needs to render.
bool display_available();

}  // namespace rbcflow
