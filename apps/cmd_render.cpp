// rbcflow render: a PNG of any saved frame of an output directory (from its vtk/ series),
// or the plot of its diagnostics.csv.
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli.h"
#include "display.h"
#include "io/case.h"
#include "io/plot.h"
#include "io/render.h"
#include "io/vtk_series.h"
#include "scenario/run_output.h"

namespace rbcflow::cli {
namespace {

namespace fs = std::filesystem;

int parse_int(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty()) throw UsageError("rbcflow render: " + what + " must be an integer, got '" + text + "'");
  return v;
}

// "WxH", each in 16..8192.
std::array<int, 2> parse_size(const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw UsageError("rbcflow render: --size must be WxH (e.g. 1280x720), got '" + text + "'");
  const std::array<int, 2> size{parse_int(text.substr(0, x), "--size width"), parse_int(text.substr(x + 1), "--size height")};
  for (const int s : size) {
    if (s < 16 || s > 8192) throw UsageError("rbcflow render: --size " + text + " is outside 16..8192");
  }
  return size;
}

RenderView parse_view(const std::string& text) {
  if (text == "side") return RenderView::side;
  if (text == "end") return RenderView::end;
  if (text == "iso") return RenderView::iso;
  throw UsageError("rbcflow render: --view must be side, end or iso, got '" + text + "'");
}

}  // namespace

int run_render(Args& args) {
  if (args.help_requested()) {
    std::printf(
        "usage: rbcflow render OUTDIR [--step S] [--view side|end|iso] [--size WxH] [--field NAME]\n"
        "                      -o PICTURE.png\n"
        "       rbcflow render OUTDIR --plot [--size WxH] -o PLOT.png\n"
        "  Renders the frame of step S (default: the last) saved in OUTDIR's VTK series: the cells\n"
        "  coloured by a point field (tension, J_S, velocity, force, cell, or none) with a colour\n"
        "  bar, the wall translucent. View, field and size default to OUTDIR/case.toml's\n"
        "  output.render_* keys. --plot draws effective viscosity and pressure gradient against\n"
        "  time from OUTDIR/diagnostics.csv instead. Without an X display it runs itself under\n"
        "  xvfb-run (docs/rendering.md).\n");
    return 0;
  }
  std::string out, step_text, view_text, size_text, field;
  if (!args.option("-o", out)) throw UsageError("rbcflow render: missing -o PICTURE.png");
  const bool plot = args.flag("--plot");
  args.option("--step", step_text);
  args.option("--view", view_text);
  args.option("--size", size_text);
  args.option("--field", field);
  const fs::path dir = args.positional("output directory (OUTDIR)");
  args.finish();
  if (!fs::is_directory(dir)) throw UsageError("rbcflow render: " + dir.string() + " is not a directory");

  if (plot) {
    if (!step_text.empty() || !view_text.empty() || !field.empty()) {
      throw UsageError("rbcflow render: --plot takes only --size and -o");
    }
    const std::array<int, 2> size = size_text.empty() ? std::array<int, 2>{1000, 700} : parse_size(size_text);
    if (!fs::exists(dir / "diagnostics.csv")) {
      throw UsageError("rbcflow render: " + (dir / "diagnostics.csv").string() + " does not exist");
    }
    ensure_display();
    plot_diagnostics(dir / "diagnostics.csv", out, size[0], size[1]);
    std::printf("%s -> %s\n", (dir / "diagnostics.csv").c_str(), out.c_str());
    return 0;
  }

  // Defaults from the case as run, when the directory has it.
  RenderOptions o;
  if (fs::exists(dir / "case.toml")) o = render_options(read_case(dir / "case.toml"));
  if (!field.empty()) o.field = field;
  if (!view_text.empty()) o.view = parse_view(view_text);
  if (!size_text.empty()) {
    const std::array<int, 2> size = parse_size(size_text);
    o.width = size[0];
    o.height = size[1];
  }
  std::optional<long> step;
  if (!step_text.empty()) step = parse_int(step_text, "--step");
  const VtkFrame frame = read_vtk_frame(dir, step);
  char label[96];
  std::snprintf(label, sizeof label, "step %ld   t = %.4g", frame.step, frame.time);
  o.label = label;
  ensure_display();
  render_png(frame.surfaces, o, out);
  std::printf("step %ld (t = %g), %s view, %s, %dx%d -> %s\n", frame.step, frame.time, to_string(o.view).c_str(),
              o.field.c_str(), o.width, o.height, out.c_str());
  return 0;
}

}  // namespace rbcflow::cli
