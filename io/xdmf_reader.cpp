#include "io/xdmf_reader.h"

#include <hdf5.h>

#include "io/hdf5_file.h"
#include "io/input_error.h"
#include "io/xdmf_writer.h"

namespace rbcflow {
namespace {

namespace fs = std::filesystem;

// Opens DIR/STEM.h5 and its /frames group; InputError naming the file otherwise.
struct Series {
  Series(const fs::path& dir, const std::string& stem) : path(dir / (stem + ".h5")) {
    if (!fs::is_regular_file(path)) throw InputError(path.string() + ": no such file (no XDMF output in " + dir.string() + ")");
    try {
      file = h5::open_file(path, false);
      if (!h5::has_attribute(file.get(), "format") ||
          h5::read_string_attribute(file.get(), "format") != "rbcflow XDMF series") {
        throw InputError(path.string() + ": not an rbcflow XDMF series");
      }
      frames = h5::open_group(file.get(), "frames");
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError(path.string() + ": cannot be read (" + e.what() + ")");
    }
  }
  h5::QuietErrors quiet;
  fs::path path;
  h5::Id file, frames;
};

}  // namespace

std::vector<XdmfFrameTime> read_xdmf_frames(const fs::path& dir, const std::string& stem) {
  const Series series(dir, stem);
  std::vector<XdmfFrameTime> out;
  for (const std::string& label : h5::children(series.frames.get())) {
    const h5::Id frame = h5::open_group(series.frames.get(), label);
    out.push_back({static_cast<long>(h5::read_int_attribute(frame.get(), "step")),
                   h5::read_double_attribute(frame.get(), "time")});
  }
  return out;
}

XdmfFrame read_xdmf_frame(const fs::path& dir, long step, const std::string& stem) {
  const Series series(dir, stem);
  const std::string label = step_label(step);
  if (!h5::exists(series.frames.get(), label)) {
    std::string steps;
    for (const XdmfFrameTime& f : read_xdmf_frames(dir, stem)) steps.append(steps.empty() ? "" : ", ").append(std::to_string(f.step));
    throw InputError(series.path.string() + ": no frame at step " + std::to_string(step) + " (saved: " + steps + ")");
  }
  const h5::Id frame = h5::open_group(series.frames.get(), label);
  XdmfFrame out;
  out.step = static_cast<long>(h5::read_int_attribute(frame.get(), "step"));
  out.time = h5::read_double_attribute(frame.get(), "time");
  for (const std::string& name : h5::children(frame.get())) {
    const h5::Id g = h5::open_group(frame.get(), name);
    Surface s{name, {h5::read_matrix(g.get(), "points"), h5::read_int_matrix(g.get(), "triangles")}, {}};
    for (const std::string& field : h5::children(g.get())) {
      if (field != "points" && field != "triangles") s.fields.push_back({field, h5::read_matrix(g.get(), field)});
    }
    out.surfaces.push_back(std::move(s));
  }
  return out;
}

}  // namespace rbcflow
