#pragma once
// VTK XML time series: DIR/vtk/<surface>_NNNNNNNN.vtp for each surface of each frame and
// DIR/rbcflow.pvd, the collection ParaView opens (one block per surface, one time per
// frame). The .pvd is replaced atomically after each frame, so it lists complete frames only.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/surface.h"

namespace rbcflow {

struct VtkSeriesEntry {
  long step = 0;
  double time = 0;
  std::string surface;
  std::string file;  // relative to DIR
};

class VtkSeriesWriter {
 public:
  // Starts DIR/STEM.pvd afresh (DIR/vtk/ is created); or, with `resume_step`, continues the
  // collection after that step (later entries and their files are removed).
  explicit VtkSeriesWriter(const std::filesystem::path& dir, std::optional<long> resume_step = std::nullopt,
                           const std::string& stem = "rbcflow");
  // Writes one frame; steps must increase.
  void write_frame(long step, double time, const std::vector<Surface>& surfaces);
  const std::vector<VtkSeriesEntry>& entries() const { return entries_; }

 private:
  void write_pvd() const;
  std::filesystem::path dir_, pvd_path_;
  std::vector<VtkSeriesEntry> entries_;
};

// The entries of DIR/STEM.pvd as written by VtkSeriesWriter; throws InputError naming the
// file when it is missing or not such a collection.
std::vector<VtkSeriesEntry> read_pvd(const std::filesystem::path& pvd);

// One saved frame read back: `step`, or the last frame when empty. Throws InputError listing
// the saved steps when `step` is not among them.
struct VtkFrame {
  long step = 0;
  double time = 0;
  std::vector<Surface> surfaces;
};
VtkFrame read_vtk_frame(const std::filesystem::path& dir, std::optional<long> step = std::nullopt,
                        const std::string& stem = "rbcflow");

}  // namespace rbcflow
