#pragma once
// An XDMF series written by XdmfWriter (xdmf_writer.h) read back from its HDF5 file: the steps
// and times of its frames, and one frame's surfaces with their point fields. For scripts (the
// Python module's read_run) and tests; ParaView reads the .xdmf itself.
#include <filesystem>
#include <string>
#include <vector>

#include "io/surface.h"

namespace rbcflow {

struct XdmfFrameTime {
  long step = 0;
  double time = 0;
};

// The frames of DIR/STEM.h5 in the order written. Throws InputError naming the file when it is
// missing or not an rbcflow XDMF series.
std::vector<XdmfFrameTime> read_xdmf_frames(const std::filesystem::path& dir, const std::string& stem = "rbcflow");

struct XdmfFrame {
  long step = 0;
  double time = 0;
  std::vector<Surface> surfaces;  // points, triangles and every point field, as written
};
// The frame of `step`; throws InputError listing the saved steps when it is not among them.
XdmfFrame read_xdmf_frame(const std::filesystem::path& dir, long step, const std::string& stem = "rbcflow");

}  // namespace rbcflow
