#include "io/xdmf_writer.h"

#include <algorithm>

#include <charconv>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/hdf5_file.h"

namespace rbcflow {

namespace fs = std::filesystem;

namespace {

std::string number(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

const char* attribute_type(long long columns) {
  switch (columns) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    default: return "Matrix";
  }
}

// <DataItem> of an HDF5 dataset, path relative to the .xdmf file.
std::string data_item(const std::string& h5_name, const std::string& dataset, long long rows, long long cols,
                      bool integer, const std::string& indent) {
  std::string dims = std::to_string(rows);
  if (cols != 1) dims.append(" ").append(std::to_string(cols));
  std::string s = indent;
  s.append("<DataItem Dimensions=\"").append(dims).append("\" NumberType=\"").append(integer ? "Int" : "Float");
  s.append("\" Precision=\"").append(integer ? "4" : "8").append("\" Format=\"HDF\">");
  s.append(h5_name).append(":").append(dataset).append("</DataItem>\n");
  return s;
}

// The series' HDF5 file, of one process or shared by ranks.
h5::Id create(const fs::path& path, const std::optional<XdmfWriter::Ranks>& ranks) {
  return ranks ? h5::create_file(path, ranks->mpi_handle) : h5::create_file(path);
}

h5::Id open(const fs::path& path, const std::optional<XdmfWriter::Ranks>& ranks) {
  return ranks ? h5::open_file(path, true, ranks->mpi_handle) : h5::open_file(path, true);
}

// This rank's rows of a surface's array (all of them in a file of one process).
h5::RowBlock rows_of(const std::optional<XdmfWriter::Ranks>& ranks, const std::string& surface, long long rows) {
  if (!ranks) return {};
  const auto [begin, end] = ranks->rows(surface, rows);
  return {begin, end};
}

}  // namespace

std::string step_label(long step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%08ld", step);
  return buf;
}

XdmfWriter::XdmfWriter(const fs::path& dir, std::optional<long> resume_step, const std::string& stem,
                       std::optional<Ranks> ranks)
    : h5_path_(dir / (stem + ".h5")), xdmf_path_(dir / (stem + ".xdmf")), ranks_(std::move(ranks)) {
  const h5::QuietErrors quiet;
  if (resume_step && fs::exists(h5_path_)) {
    resume(*resume_step);
  } else {
    const h5::Id file = create(h5_path_, ranks_);
    h5::write_attribute(file.get(), "format", std::string("rbcflow XDMF series"));
    h5::create_group(file.get(), "frames");
  }
  write_xml();
}

bool XdmfWriter::shared_by_ranks() { return h5::parallel_io(); }

void XdmfWriter::resume(long step) {
  try {
    const h5::Id file = open(h5_path_, ranks_);
    const h5::Id all = h5::open_group(file.get(), "frames");
    for (const std::string& label : h5::children(all.get())) {
      const h5::Id frame = h5::open_group(all.get(), label);
      FrameRecord rec;
      rec.step = static_cast<long>(h5::read_int_attribute(frame.get(), "step"));
      rec.time = h5::read_double_attribute(frame.get(), "time");
      if (rec.step > step) {
        h5::remove(all.get(), label);
        continue;
      }
      for (const std::string& name : h5::children(frame.get())) {
        const h5::Id g = h5::open_group(frame.get(), name);
        SurfaceRecord s{name, static_cast<long long>(h5::shape(g.get(), "points")[0]),
                        static_cast<long long>(h5::shape(g.get(), "triangles")[0]), {}};
        for (const std::string& field : h5::children(g.get())) {
          if (field == "points" || field == "triangles") continue;
          const auto dims = h5::shape(g.get(), field);
          s.fields.push_back({field, dims.size() == 2 ? static_cast<long long>(dims[1]) : 1});
        }
        rec.surfaces.push_back(std::move(s));
      }
      frames_.push_back(std::move(rec));
    }
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot continue the XDMF series " + h5_path_.string() + ": " + e.what());
  }
}

void XdmfWriter::write_frame(long step, double time, const std::vector<Surface>& surfaces,
                             const std::map<std::string, SurfacePart>& parts) {
  if (!parts.empty() && !(ranks_ && ranks_->all))
    throw std::invalid_argument("XdmfWriter: parts of a surface are written by ranks together only");
  for (const auto& [name, part] : parts) {
    const auto s = std::find_if(surfaces.begin(), surfaces.end(), [&](const Surface& x) { return x.name == name; });
    if (s == surfaces.end() || part.points_begin < 0 || part.triangles_begin < 0 ||
        part.points_begin + s->mesh.num_points() > part.points ||
        part.triangles_begin + s->mesh.num_triangles() > part.triangles)
      throw std::invalid_argument("XdmfWriter: the part of surface " + name + " does not fit it");
  }
  if (!frames_.empty() && step <= frames_.back().step) {
    throw std::invalid_argument("XdmfWriter: step " + std::to_string(step) + " after step " +
                                std::to_string(frames_.back().step));
  }
  for (const Surface& s : surfaces) {
    validate(s);
    for (const SurfaceField& f : s.fields) {
      if (f.name == "points" || f.name == "triangles") {
        throw std::invalid_argument("XdmfWriter: a field may not be called " + f.name);
      }
    }
  }
  const h5::QuietErrors quiet;
  const std::string label = step_label(step);
  FrameRecord rec{step, time, {}};
  try {
    const h5::Id file = open(h5_path_, ranks_);
    const h5::Id all = h5::open_group(file.get(), "frames");
    const h5::Id frame = h5::create_group(all.get(), label);
    h5::write_attribute(frame.get(), "step", static_cast<long long>(step));
    h5::write_attribute(frame.get(), "time", time);
    for (const Surface& s : surfaces) {
      const h5::Id g = h5::create_group(frame.get(), s.name);
      const std::string base = "/frames/" + label + "/" + s.name;
      LastMesh next{s.mesh, base + "/points", base + "/triangles"};
      const auto it = last_.find(s.name);
      bool same_points = it != last_.end() && it->second.mesh.points.rows() == s.mesh.points.rows() &&
                         it->second.mesh.points == s.mesh.points;
      bool same_triangles = it != last_.end() && it->second.mesh.triangles.rows() == s.mesh.triangles.rows() &&
                            it->second.mesh.triangles == s.mesh.triangles;
      // This rank's rows of the surface's arrays: its part's, or its share of the whole.
      const auto part = parts.find(s.name);
      h5::RowBlock point_rows = rows_of(ranks_, s.name, s.mesh.num_points());
      h5::RowBlock triangle_rows = rows_of(ranks_, s.name, s.mesh.num_triangles());
      long long points = s.mesh.num_points(), triangles = s.mesh.num_triangles();
      if (part != parts.end()) {
        const SurfacePart& p = part->second;
        point_rows = {p.points_begin, p.points_begin + s.mesh.num_points(), p.points};
        triangle_rows = {p.triangles_begin, p.triangles_begin + s.mesh.num_triangles(), p.triangles};
        points = p.points;
        triangles = p.triangles;
        same_points = ranks_->all(same_points);
        same_triangles = ranks_->all(same_triangles);
      }
      if (same_points) {
        next.points_path = it->second.points_path;
        h5::soft_link(g.get(), "points", next.points_path);
      } else {
        h5::write_matrix(g.get(), "points", Eigen::MatrixXd(s.mesh.points), false, point_rows);
      }
      if (same_triangles) {
        next.triangles_path = it->second.triangles_path;
        h5::soft_link(g.get(), "triangles", next.triangles_path);
      } else {
        h5::write_matrix(g.get(), "triangles", Eigen::MatrixXi(s.mesh.triangles), triangle_rows);
      }
      SurfaceRecord sr{s.name, points, triangles, {}};
      for (const SurfaceField& f : s.fields) {
        h5::write_matrix(g.get(), f.name, f.values, true, point_rows);
        sr.fields.push_back({f.name, static_cast<long long>(f.values.cols())});
      }
      last_[s.name] = std::move(next);
      rec.surfaces.push_back(std::move(sr));
    }
    h5::flush(file.get());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write step " + std::to_string(step) + " to " + h5_path_.string() + ": " +
                             e.what());
  }
  frames_.push_back(std::move(rec));
  write_xml();
}

void XdmfWriter::write_xml() const {
  if (ranks_ && ranks_->rank != 0) return;
  const std::string h5 = h5_path_.filename().string();
  std::string x = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  x.append("<Xdmf Version=\"3.0\">\n  <Domain>\n");
  x.append("    <Grid Name=\"rbcflow\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (const FrameRecord& f : frames_) {
    const std::string label = step_label(f.step);
    x.append("      <Grid Name=\"step_").append(label).append("\" GridType=\"Collection\" CollectionType=\"Spatial\">\n");
    x.append("        <Time Value=\"").append(number(f.time)).append("\" />\n");
    for (const SurfaceRecord& s : f.surfaces) {
      const std::string base = "/frames/" + label + "/" + s.name + "/";
      x.append("        <Grid Name=\"").append(s.name).append("\" GridType=\"Uniform\">\n");
      x.append("          <Topology TopologyType=\"Triangle\" NumberOfElements=\"")
          .append(std::to_string(s.triangles))
          .append("\">\n");
      x.append(data_item(h5, base + "triangles", s.triangles, 3, true, "            "));
      x.append("          </Topology>\n          <Geometry GeometryType=\"XYZ\">\n");
      x.append(data_item(h5, base + "points", s.points, 3, false, "            "));
      x.append("          </Geometry>\n");
      for (const FieldRecord& a : s.fields) {
        x.append("          <Attribute Name=\"").append(a.name).append("\" AttributeType=\"");
        x.append(attribute_type(a.columns)).append("\" Center=\"Node\">\n");
        x.append(data_item(h5, base + a.name, s.points, a.columns, false, "            "));
        x.append("          </Attribute>\n");
      }
      x.append("        </Grid>\n");
    }
    x.append("      </Grid>\n");
  }
  x.append("    </Grid>\n  </Domain>\n</Xdmf>\n");
  write_atomically(xdmf_path_, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << x;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + xdmf_path_.string());
  });
}

}  // namespace rbcflow
