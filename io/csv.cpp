#include "io/csv.h"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.h"

namespace rbcflow {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string::size_type start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

std::string join(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line.append(i ? "," : "").append(fields[i]);
  return line;
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Keeps the header and the rows of `path` with step <= resume_step (rewritten atomically).
// A file written by an earlier version has the leading columns of today's header (columns are
// only ever added at the end): its rows are kept, with empty fields for the new columns.
void truncate_after(const fs::path& path, const std::string& header, long resume_step) {
  const std::vector<std::string> lines = lines_of(path);
  const std::size_t columns = split(header).size();
  const bool leading = !lines.empty() && header.starts_with(lines.front()) &&
                       (header.size() == lines.front().size() || header[lines.front().size()] == ',');
  if (!leading) throw std::runtime_error("cannot continue " + path.string() + ": its header is not that of rbcflow");
  const std::size_t old_columns = split(lines.front()).size();
  const std::string padding(columns - old_columns, ',');
  std::string kept = header + "\n";
  for (std::size_t i = 1; i < lines.size(); ++i) {
    long step = 0;
    const std::string& l = lines[i];
    const auto r = std::from_chars(l.data(), l.data() + l.size(), step);
    // A row cut short by a crash has no newline and fails the field count later: drop it too.
    if (r.ec != std::errc() || step > resume_step) continue;
    if (split(l).size() != old_columns) continue;
    kept.append(l).append(padding).append("\n");
  }
  write_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << kept;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path.string());
  });
}

std::string csv_integer(const std::optional<int>& x) { return x ? std::to_string(*x) : std::string(); }

// The fields of one row, in column order.
struct Row {
  std::vector<std::string> fields;
  Row& add(std::string s) {
    fields.push_back(std::move(s));
    return *this;
  }
  Row& add(const Vec3& v) { return add(csv_number(v[0])).add(csv_number(v[1])).add(csv_number(v[2])); }
};

}  // namespace

std::string csv_number(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string csv_number(const std::optional<double>& x) { return x ? csv_number(*x) : std::string(); }

const std::vector<std::string>& diagnostics_columns() {
  static const std::vector<std::string> columns = {
      "step", "time", "dt", "mean_velocity_x", "mean_velocity_y", "mean_velocity_z",
      "pressure_gradient_x", "pressure_gradient_y", "pressure_gradient_z", "effective_viscosity",
      "tube_hematocrit", "max_volume_error", "max_area_error", "gmres_cells", "gmres_wall",
      "wall_residual", "seconds", "collision_pairs", "wall_contacts", "collision_displacement",
      "tube_velocity", "pseudo_shear_rate_per_s", "discharge_hematocrit", "max_area_strain", "cell_free_layer", "min_wall_gap",
      "max_volume_correction", "max_contact_traction", "contact_cells",
      "max_area_strain_cell"};
  return columns;
}

const std::vector<std::string>& cells_columns() {
  static const std::vector<std::string> columns = {
      "step", "time", "cell", "centroid_x", "centroid_y", "centroid_z", "velocity_x", "velocity_y",
      "velocity_z", "volume", "area", "taylor_deformation", "inclination"};
  return columns;
}

const std::vector<std::string>& branches_columns() {
  static const std::vector<std::string> columns = {"step", "time", "branch", "flow_rate", "cells", "cells_passed"};
  return columns;
}

CsvWriter::CsvWriter(fs::path path, std::vector<std::string> columns, std::optional<long> resume_step)
    : path_(std::move(path)), columns_(columns.size()), file_(nullptr, &std::fclose) {
  const std::string header = join(columns);
  const bool resume = resume_step && fs::exists(path_);
  if (resume) truncate_after(path_, header, *resume_step);
  file_.reset(std::fopen(path_.c_str(), resume ? "a" : "w"));
  if (!file_) throw std::runtime_error("cannot write " + path_.string() + ": " + std::strerror(errno));
  if (!resume) write(columns);
}

void CsvWriter::write(const std::vector<std::string>& fields) {
  if (fields.size() != columns_) {
    throw std::invalid_argument("CsvWriter: " + std::to_string(fields.size()) + " fields for " +
                                std::to_string(columns_) + " columns of " + path_.string());
  }
  const std::string line = join(fields) + "\n";
  if (std::fputs(line.c_str(), file_.get()) == EOF || std::fflush(file_.get()) != 0) {
    throw std::runtime_error("cannot write " + path_.string() + ": " + std::strerror(errno));
  }
}

DiagnosticsCsv::DiagnosticsCsv(const fs::path& path, std::optional<long> resume_step)
    : csv_(path, diagnostics_columns(), resume_step) {}

void DiagnosticsCsv::write(const DiagnosticsRow& r) {
  Row row;
  row.add(std::to_string(r.step)).add(csv_number(r.time)).add(csv_number(r.dt));
  row.add(r.mean_velocity).add(r.pressure_gradient);
  row.add(csv_number(r.effective_viscosity)).add(csv_number(r.tube_hematocrit));
  row.add(csv_number(r.max_volume_error)).add(csv_number(r.max_area_error));
  row.add(std::to_string(r.gmres_cells)).add(csv_integer(r.gmres_wall));
  row.add(csv_number(r.wall_residual)).add(csv_number(r.seconds));
  row.add(csv_integer(r.collision_pairs)).add(csv_integer(r.wall_contacts));
  row.add(csv_number(r.collision_displacement));
  row.add(csv_number(r.tube_velocity)).add(csv_number(r.pseudo_shear_rate_per_s));
  row.add(csv_number(r.discharge_hematocrit)).add(csv_number(r.max_area_strain));
  row.add(csv_number(r.cell_free_layer)).add(csv_number(r.min_wall_gap));
  row.add(csv_number(r.max_volume_correction));
  row.add(csv_number(r.max_contact_traction)).add(csv_integer(r.contact_cells));
  row.add(csv_integer(r.max_area_strain_cell));
  csv_.write(row.fields);
}

CellsCsv::CellsCsv(const fs::path& path, std::optional<long> resume_step)
    : csv_(path, cells_columns(), resume_step) {}

void CellsCsv::write(const std::vector<CellRow>& frame) {
  for (const CellRow& r : frame) {
    Row row;
    row.add(std::to_string(r.step)).add(csv_number(r.time)).add(std::to_string(r.cell));
    row.add(r.centroid).add(r.velocity).add(csv_number(r.volume)).add(csv_number(r.area));
    row.add(csv_number(r.taylor_deformation)).add(csv_number(r.inclination));
    csv_.write(row.fields);
  }
}

BranchesCsv::BranchesCsv(const fs::path& path, std::optional<long> resume_step)
    : csv_(path, branches_columns(), resume_step) {}

void BranchesCsv::write(const std::vector<BranchRow>& rows) {
  for (const BranchRow& r : rows) {
    csv_.write({std::to_string(r.step), csv_number(r.time), std::to_string(r.branch), csv_number(r.flow_rate),
                std::to_string(r.cells), std::to_string(r.cells_passed)});
  }
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return i;
  }
  throw std::runtime_error(path.string() + ": no column '" + name + "'");
}

CsvTable read_csv(const fs::path& path) {
  if (!fs::is_regular_file(path)) throw std::runtime_error("cannot read " + path.string() + ": no such file");
  const std::vector<std::string> lines = lines_of(path);
  if (lines.empty()) throw std::runtime_error("cannot read " + path.string() + ": the file is empty");
  CsvTable t;
  t.path = path;
  t.columns = split(lines.front());
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::vector<std::string> row = split(lines[i]);
    if (row.size() == t.columns.size()) t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace rbcflow
