// compare_runs CASE.toml DIR_A DIR_B STEP TOLERANCE [FLOOR]: exit 0 when the two output
// directories hold the same checkpoint at STEP (every matrix within TOLERANCE relative to its
// largest entry), the same frames in rbcflow.h5 where both have one (the same steps, surfaces
// and triangles; points and fields within TOLERANCE relative to the largest entry of each) and
// the same diagnostics.csv rows (every column but `seconds`, within TOLERANCE relative to the
// larger magnitude, the components of a vector (`name_x`, `name_y`, `name_z`) relative to the
// vector's largest component, or within FLOOR absolute: default 0) and, where a run has cells,
// the same cells.csv rows at the steps and cells both have (every column but `inclination`, the
// same way: the inclination of a cell whose two longest semi-axes are equal, a red cell at
// rest, is rounding's choice); runs that sum in another
// order differ by rounding in columns that are rounding errors themselves, such as
// max_volume_error ~ 1e-16); prints the largest differences. A NaN against a number (or an empty field
// against one) is an infinite difference, never dropped; NaN against NaN is no difference. For
// the restart test: an uninterrupted run against one stopped and restarted from a checkpoint.
// Velocities a checkpoint holds in the order of cells/velocity_order (one written by several
// ranks) are compared in cell order.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/case.h"
#include "io/checkpoint.h"
#include "io/csv.h"
#include "io/xdmf_reader.h"
#include "io/xdmf_writer.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

// |x - y| where both are numbers; 0 where both are NaN; infinite where only one is.
double difference(double x, double y) {
  if (std::isnan(x) || std::isnan(y)) return std::isnan(x) && std::isnan(y) ? 0.0 : INFINITY;
  return std::abs(x - y);
}

double max_difference(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
  if (x.rows() != y.rows() || x.cols() != y.cols()) return INFINITY;
  double d = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i) d = std::max(d, difference(x.data()[i], y.data()[i]));
  return d;
}

// |x - y| relative to scale (at least |x| and |y|), or 0 within floor.
double field_difference(const std::string& a, const std::string& b, double scale, double floor) {
  if (a.empty() || b.empty()) return a.empty() && b.empty() ? 0.0 : INFINITY;
  const double x = std::stod(a), y = std::stod(b);
  const double d = difference(x, y);
  if (d <= floor) return 0.0;
  return d == 0.0 || std::isinf(d) ? d : d / std::max({std::abs(x), std::abs(y), scale, 1e-300});
}

// The magnitude a column's entries are compared against in row rt of t and ru of u: a vector's
// largest component in either row for the components of a vector (a small lateral component of
// the pressure gradient moves by the rounding of the whole vector), else 0 (the entries' own).
double column_scale(const CsvTable& t, std::size_t rt, const CsvTable& u, std::size_t ru, std::size_t k) {
  const std::string& name = t.columns[k];
  if (name.size() < 3 || name[name.size() - 2] != '_' || std::string("xyz").find(name.back()) == std::string::npos)
    return 0.0;
  double scale = 0;
  for (const char c : std::string("xyz")) {
    const std::string component = name.substr(0, name.size() - 1) + c;
    const auto it = std::find(t.columns.begin(), t.columns.end(), component);
    if (it == t.columns.end()) return 0.0;
    const std::size_t j = static_cast<std::size_t>(it - t.columns.begin());
    for (const std::string* f : {&t.rows[rt][j], &u.rows[ru][j]}) {
      const std::string& field = *f;
      if (!field.empty() && std::isfinite(std::stod(field))) scale = std::max(scale, std::abs(std::stod(field)));
    }
  }
  return scale;
}

double relative_max_difference(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
  const double d = max_difference(x, y);
  const double scale = x.size() ? x.cwiseAbs().maxCoeff() : 0.0;
  return scale > 0 && std::isfinite(d) ? d / scale : d;
}

// The frames of the two runs' rbcflow.h5 (where both have one) agree at every step both hold
// (a run restarted into another directory holds only the frames after its restart).
bool same_frames(const std::string& a, const std::string& b, double tolerance) {
  if (!std::filesystem::exists(a + "/rbcflow.h5") || !std::filesystem::exists(b + "/rbcflow.h5")) return true;
  const std::vector<XdmfFrameTime> fa = read_xdmf_frames(a), fb = read_xdmf_frames(b);
  std::vector<long> common;
  for (const XdmfFrameTime& x : fa)
    for (const XdmfFrameTime& y : fb)
      if (x.step == y.step) common.push_back(x.step);
  bool ok = !common.empty();
  double worst = 0;
  for (const long step : common) {
    const XdmfFrame x = read_xdmf_frame(a, step), y = read_xdmf_frame(b, step);
    ok = ok && x.time == y.time && x.surfaces.size() == y.surfaces.size();
    for (std::size_t k = 0; ok && k < x.surfaces.size(); ++k) {
      const Surface &p = x.surfaces[k], &q = y.surfaces[k];
      ok = p.name == q.name && p.mesh.triangles == q.mesh.triangles && p.fields.size() == q.fields.size();
      worst = std::max(worst, relative_max_difference(p.mesh.points, q.mesh.points));
      for (std::size_t f = 0; ok && f < p.fields.size(); ++f) {
        ok = p.fields[f].name == q.fields[f].name;
        worst = std::max(worst, relative_max_difference(p.fields[f].values, q.fields[f].values));
      }
    }
  }
  std::printf("rbcflow.h5: %zu frames against %zu, %zu at the same steps: points and fields max |a - b| / max |a| = "
              "%.3e%s\n", fa.size(), fb.size(), common.size(), worst, ok ? "" : " (times, surfaces or triangles differ)");
  return ok && worst <= tolerance;
}

// The difference of row ra of da from row rb of db over every column but `skip`, relative to
// the larger magnitude (a vector's components to its largest), 0 within floor; the worst
// column's name goes to `column` when it is worse than `worst`.
void row_difference(const CsvTable& da, std::size_t ra, const CsvTable& db, std::size_t rb, std::size_t skip,
                    double floor, double& worst, std::string& column) {
  for (std::size_t k = 0; k < da.columns.size(); ++k) {
    if (k == skip || da.rows[ra][k] == db.rows[rb][k]) continue;
    const double d = field_difference(da.rows[ra][k], db.rows[rb][k], column_scale(da, ra, db, rb, k), floor);
    if (d > worst) {
      worst = d;
      column = da.columns[k];
    }
  }
}

// diagnostics.csv of both directories: the same rows, every column but `seconds` within
// tolerance.
bool same_diagnostics(const std::string& a, const std::string& b, double tolerance, double floor) {
  const CsvTable da = read_csv(a + "/diagnostics.csv"), db = read_csv(b + "/diagnostics.csv");
  if (da.rows.size() != db.rows.size() || da.columns != db.columns) {
    std::printf("diagnostics.csv: %zu rows against %zu\n", da.rows.size(), db.rows.size());
    return false;
  }
  double worst = 0;
  std::string column;
  for (std::size_t r = 0; r < da.rows.size(); ++r) row_difference(da, r, db, r, da.column("seconds"), floor, worst, column);
  std::printf("diagnostics.csv: %zu rows, max relative difference %.3e%s\n", da.rows.size(), worst,
              column.empty() ? "" : (" (" + column + ")").c_str());
  return worst <= tolerance;
}

// cells.csv of both directories, as the frames: the rows of the same step and cell in both
// (one run may have written more frames), every column but `inclination` within tolerance.
bool same_cell_rows(const std::string& a, const std::string& b, double tolerance, double floor) {
  if (!fs::exists(a + "/cells.csv") || !fs::exists(b + "/cells.csv")) {
    std::printf("cells.csv: in one directory only\n");
    return false;
  }
  const CsvTable da = read_csv(a + "/cells.csv"), db = read_csv(b + "/cells.csv");
  if (da.columns != db.columns) {
    std::printf("cells.csv: other columns\n");
    return false;
  }
  const std::size_t step = da.column("step"), cell = da.column("cell");
  std::map<std::pair<std::string, std::string>, std::size_t> in_b;
  for (std::size_t r = 0; r < db.rows.size(); ++r) in_b[{db.rows[r][step], db.rows[r][cell]}] = r;
  double worst = 0;
  std::string column;
  std::size_t common = 0;
  for (std::size_t r = 0; r < da.rows.size(); ++r) {
    const auto it = in_b.find({da.rows[r][step], da.rows[r][cell]});
    if (it == in_b.end()) continue;
    ++common;
    row_difference(da, r, db, it->second, da.column("inclination"), floor, worst, column);
  }
  std::printf("cells.csv: %zu rows against %zu, %zu of the same step and cell: max relative difference %.3e%s\n",
              da.rows.size(), db.rows.size(), common, worst, column.empty() ? "" : (" (" + column + ")").c_str());
  return common > 0 && worst <= tolerance;
}

// A checkpoint's item; the velocities in cell order where the checkpoint holds them in that of
// cells/velocity_order (written by several ranks: docs/case-format.md, "Checkpoints").
Eigen::MatrixXd item_in_cell_order(const Checkpoint& k, const std::string& name) {
  const Eigen::MatrixXd& m = k.matrix(name);
  const bool velocity = name == "cells/previous_velocity" || name == "cells/older_velocity" || name == "cells/oldest_velocity";
  if (!velocity || !k.has("cells/velocity_order")) return m;
  const Eigen::MatrixXi& order = k.int_matrix("cells/velocity_order");
  if (order.size() == 0 || m.rows() % order.size() != 0 || order.minCoeff() < 0 || order.maxCoeff() >= order.size())
    return m;  // not an order of the cells: compared as it is
  const Eigen::Index np = m.rows() / order.size();
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (Eigen::Index p = 0; p < order.size(); ++p) out.middleRows(order(p) * np, np) = m.middleRows(p * np, np);
  return out;
}

// The items but the order of the velocities' rows, which the ranks of a run choose.
std::vector<std::string> state_items(const Checkpoint& k) {
  std::vector<std::string> names = k.names();
  std::erase(names, std::string("cells/velocity_order"));
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6 && argc != 7) {
    std::fprintf(stderr, "usage: compare_runs CASE.toml DIR_A DIR_B STEP TOLERANCE [FLOOR]\n");
    return 2;
  }
  const double floor = argc == 7 ? std::stod(argv[6]) : 0.0;
  const Case c = read_case(argv[1]);
  const std::string a = argv[2], b = argv[3], label = "checkpoints/step_" + step_label(std::stol(argv[4])) + ".h5";
  const double tolerance = std::stod(argv[5]);
  const Checkpoint ka = Checkpoint::read(a + "/" + label, case_fingerprint(c));
  const Checkpoint kb = Checkpoint::read(b + "/" + label, case_fingerprint(c));
  double worst = 0;
  bool ok = state_items(ka) == state_items(kb);
  if (!ok) std::printf("the checkpoints hold different items\n");
  for (const std::string& name : state_items(ka)) {
    if (!kb.has(name)) continue;
    double d = 0;
    try {
      d = max_difference(item_in_cell_order(ka, name), item_in_cell_order(kb, name));
    } catch (const CheckpointError&) {
      continue;  // not a double matrix: compared below when an integer or real
    }
    const double scale = ka.matrix(name).size() ? ka.matrix(name).cwiseAbs().maxCoeff() : 0.0;
    const double relative = scale > 0 && std::isfinite(d) ? d / scale : d;
    std::printf("%-32s max |a - b| = %.3e  (/ max |a| = %.3e)\n", name.c_str(), d, relative);
    worst = std::max(worst, relative);
  }
  if (ka.integer("steps") != kb.integer("steps") || ka.real("time") != kb.real("time")) ok = false;
  ok = same_frames(a, b, tolerance) && ok;

  ok = same_diagnostics(a, b, tolerance, floor) && ok;
  if (fs::exists(a + "/cells.csv") || fs::exists(b + "/cells.csv")) ok = same_cell_rows(a, b, tolerance, floor) && ok;
  ok = ok && worst <= tolerance;
  std::printf("%s\n", ok ? "same" : "DIFFERENT");
  return ok ? 0 : 1;
}
