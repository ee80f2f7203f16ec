#pragma once
// XDMF 3 time series over one HDF5 file: DIR/rbcflow.h5 holds the data, DIR/rbcflow.xdmf the
// XML that ParaView opens (Xdmf3 reader). The only code in rbcflow that writes XML for XDMF.
//
// Layout of the HDF5 file: /frames/NNNNNNNN (the step, 8 digits; attributes `step`, `time`)
// holds one group per surface with datasets `points` (n x 3), `triangles` (t x 3, int32) and
// one dataset per point field (n, n x 3 or n x k). Points and triangles equal to those of
// the surface's previous frame are soft links to them (the wall, the cells' connectivity).
// The XML: a temporal collection of spatial collections, one uniform grid per surface,
// dataset paths relative to the .xdmf file.
//
// A crash leaves a readable series: the HDF5 file is open only while a frame is written (so
// ParaView can read it meanwhile, and a kill between frames leaves it closed); after each
// frame it is flushed and closed, then the XML, which lists only complete frames, is
// replaced atomically.
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/surface.h"

namespace rbcflow {

class XdmfWriter {
 public:
  // The ranks of a run writing the series together (parallel HDF5, io/hdf5_file.h): every rank
  // makes the same writer and the same write_frame calls with the same surfaces; `rows` says
  // which rows of a surface's arrays (its name and row count: points or triangles) this rank
  // writes. Rank 0 writes the XML.
  struct Ranks {
    int mpi_handle = -1;
    int rank = 0;
    std::function<std::pair<long long, long long>(const std::string& surface, long long rows)> rows;
    // Whether `mine` holds on every rank (collective): the ranks agree whether the parts of a
    // surface (below) repeat the last frame's points or triangles.
    std::function<bool(bool mine)> all;
  };
  // A surface of which each rank gives write_frame only its rows: its points are the rows from
  // `points_begin` on of `points` in all, its triangles likewise (their point numbers the whole
  // surface's); the ranks' parts cover the surface once.
  struct SurfacePart {
    long long points_begin = 0, points = 0, triangles_begin = 0, triangles = 0;
  };

  // Starts DIR/STEM.h5 and DIR/STEM.xdmf afresh; or, with `resume_step`, continues them after
  // that step (later frames, left by a run that went past its last checkpoint, are dropped).
  explicit XdmfWriter(const std::filesystem::path& dir, std::optional<long> resume_step = std::nullopt,
                      const std::string& stem = "rbcflow", std::optional<Ranks> ranks = std::nullopt);

  // Writes one frame; steps must increase. `parts`: the surfaces of which this rank gives only
  // its part, by name (ranks only).
  void write_frame(long step, double time, const std::vector<Surface>& surfaces,
                   const std::map<std::string, SurfacePart>& parts = {});
  // Whether this build can write a series from several ranks (parallel HDF5).
  static bool shared_by_ranks();

  int frames() const { return static_cast<int>(frames_.size()); }
  const std::filesystem::path& xdmf_path() const { return xdmf_path_; }
  const std::filesystem::path& h5_path() const { return h5_path_; }

 private:
  struct FieldRecord {
    std::string name;
    long long columns;
  };
  struct SurfaceRecord {
    std::string name;
    long long points = 0, triangles = 0;
    std::vector<FieldRecord> fields;
  };
  struct FrameRecord {
    long step = 0;
    double time = 0;
    std::vector<SurfaceRecord> surfaces;
  };
  // The last points and triangles written for a surface, and where.
  struct LastMesh {
    TriangleMesh mesh;
    std::string points_path, triangles_path;
  };

  void resume(long step);
  void write_xml() const;

  std::filesystem::path h5_path_, xdmf_path_;
  std::vector<FrameRecord> frames_;
  std::map<std::string, LastMesh> last_;
  std::optional<Ranks> ranks_;
};

// "00000100": the zero-padded step used in HDF5 groups and file names.
std::string step_label(long step);

}  // namespace rbcflow
