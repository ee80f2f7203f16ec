#include "io/vtk_series.h"

#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <charconv>
#include <fstream>
#include <set>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/input_error.h"
#include "io/vtk_polydata.h"
#include "io/xdmf_writer.h"

namespace rbcflow {

namespace fs = std::filesystem;

namespace {

std::string number(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace

VtkSeriesWriter::VtkSeriesWriter(const fs::path& dir, std::optional<long> resume_step, const std::string& stem)
    : dir_(dir), pvd_path_(dir / (stem + ".pvd")) {
  std::error_code ec;
  fs::create_directories(dir_ / "vtk", ec);
  if (ec) throw std::runtime_error("cannot create " + (dir_ / "vtk").string() + ": " + ec.message());
  if (resume_step && fs::exists(pvd_path_)) {
    for (VtkSeriesEntry& e : read_pvd(pvd_path_)) {
      if (e.step <= *resume_step) {
        entries_.push_back(std::move(e));
      } else {
        fs::remove(dir_ / e.file, ec);
      }
    }
  }
  write_pvd();
}

void VtkSeriesWriter::write_frame(long step, double time, const std::vector<Surface>& surfaces) {
  if (!entries_.empty() && step <= entries_.back().step) {
    throw std::invalid_argument("VtkSeriesWriter: step " + std::to_string(step) + " after step " +
                                std::to_string(entries_.back().step));
  }
  for (const Surface& s : surfaces) validate(s);
  std::vector<VtkSeriesEntry> added;
  for (const Surface& s : surfaces) {
    const std::string file = "vtk/" + s.name + "_" + step_label(step) + ".vtp";
    write_vtp(dir_ / file, s.mesh, s.fields);
    added.push_back({step, time, s.name, file});
  }
  entries_.insert(entries_.end(), added.begin(), added.end());
  write_pvd();
}

void VtkSeriesWriter::write_pvd() const {
  std::string x = "<?xml version=\"1.0\"?>\n";
  x.append("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n");
  long step = -1;
  int part = 0;
  for (const VtkSeriesEntry& e : entries_) {
    part = e.step == step ? part + 1 : 0;
    step = e.step;
    x.append("    <DataSet timestep=\"").append(number(e.time)).append("\" step=\"").append(std::to_string(e.step));
    x.append("\" part=\"").append(std::to_string(part)).append("\" name=\"").append(e.surface);
    x.append("\" file=\"").append(e.file).append("\"/>\n");
  }
  x.append("  </Collection>\n</VTKFile>\n");
  write_atomically(pvd_path_, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << x;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + pvd_path_.string());
  });
}

std::vector<VtkSeriesEntry> read_pvd(const fs::path& pvd) {
  if (!fs::is_regular_file(pvd)) throw InputError("cannot read " + pvd.string() + ": no such file");
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromFile(pvd.c_str()));
  vtkXMLDataElement* collection = root ? root->FindNestedElementWithName("Collection") : nullptr;
  if (!collection || std::string(root->GetName()) != "VTKFile") {
    throw InputError("cannot read " + pvd.string() + ": not a VTK collection (.pvd) file");
  }
  std::vector<VtkSeriesEntry> entries;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* d = collection->GetNestedElement(i);
    const char* time = d->GetAttribute("timestep");
    const char* step = d->GetAttribute("step");
    const char* name = d->GetAttribute("name");
    const char* file = d->GetAttribute("file");
    if (std::string(d->GetName()) != "DataSet" || !time || !step || !name || !file) {
      throw InputError("cannot read " + pvd.string() + ": DataSet " + std::to_string(i) +
                               " lacks timestep, step, name or file");
    }
    entries.push_back({std::stol(step), std::stod(time), name, file});
  }
  return entries;
}

VtkFrame read_vtk_frame(const fs::path& dir, std::optional<long> step, const std::string& stem) {
  const fs::path pvd = dir / (stem + ".pvd");
  const std::vector<VtkSeriesEntry> entries = read_pvd(pvd);
  if (entries.empty()) throw InputError(pvd.string() + " lists no frames yet");
  const long wanted = step.value_or(entries.back().step);
  VtkFrame frame{wanted, 0, {}};
  std::set<long> steps;
  for (const VtkSeriesEntry& e : entries) {
    if (e.step == wanted) {
      frame.time = e.time;
      frame.surfaces.push_back(read_vtp_surface(dir / e.file, e.surface));
    }
    steps.insert(e.step);
  }
  if (frame.surfaces.empty()) {
    std::string saved;
    for (const long s : steps) saved.append(" ").append(std::to_string(s));
    throw InputError("no frame at step " + std::to_string(wanted) + " in " + pvd.string() +
                             " (saved steps:" + saved + ")");
  }
  return frame;
}

}  // namespace rbcflow
