#include "io/surface.h"

#include <set>
#include <stdexcept>

namespace rbcflow {
namespace {

bool plain_name(const std::string& name) {
  if (name.empty()) return false;
  for (const char ch : name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

void validate(const Surface& s) {
  if (!plain_name(s.name)) throw std::invalid_argument("surface name '" + s.name + "' is not [A-Za-z0-9_]+");
  std::set<std::string> names;
  for (const SurfaceField& f : s.fields) {
    if (!plain_name(f.name)) {
      throw std::invalid_argument("surface " + s.name + ": field name '" + f.name + "' is not [A-Za-z0-9_]+");
    }
    if (!names.insert(f.name).second) throw std::invalid_argument("surface " + s.name + ": field " + f.name + " twice");
    if (f.values.rows() != s.mesh.num_points()) {
      throw std::invalid_argument("surface " + s.name + ": field " + f.name + " has " +
                                  std::to_string(f.values.rows()) + " rows for " +
                                  std::to_string(s.mesh.num_points()) + " points");
    }
  }
}

Surface merge_surfaces(const std::string& name, const std::vector<Surface>& parts, const std::string& id_field) {
  Surface m;
  m.name = name;
  int points = 0, triangles = 0;
  for (const Surface& p : parts) {
    points += p.mesh.num_points();
    triangles += p.mesh.num_triangles();
  }
  m.mesh.points.resize(points, 3);
  m.mesh.triangles.resize(triangles, 3);
  Eigen::MatrixXd ids(points, 1);
  if (!parts.empty()) {
    for (const SurfaceField& f : parts.front().fields) m.fields.push_back({f.name, Eigen::MatrixXd(points, f.values.cols())});
  }
  int p0 = 0, t0 = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const Surface& part = parts[k];
    validate(part);
    const int n = part.mesh.num_points(), t = part.mesh.num_triangles();
    m.mesh.points.middleRows(p0, n) = part.mesh.points;
    m.mesh.triangles.middleRows(t0, t) = part.mesh.triangles.array() + p0;
    ids.middleRows(p0, n).setConstant(static_cast<double>(k));
    if (part.fields.size() != m.fields.size()) {
      throw std::invalid_argument("merge_surfaces: part " + std::to_string(k) + " has other fields than part 0");
    }
    for (std::size_t f = 0; f < part.fields.size(); ++f) {
      if (part.fields[f].name != m.fields[f].name || part.fields[f].values.cols() != m.fields[f].values.cols()) {
        throw std::invalid_argument("merge_surfaces: part " + std::to_string(k) + " has other fields than part 0");
      }
      m.fields[f].values.middleRows(p0, n) = part.fields[f].values;
    }
    p0 += n;
    t0 += t;
  }
  m.fields.push_back({id_field, ids});
  validate(m);
  return m;
}

}  // namespace rbcflow
