#include "geometry/vessel/gmsh_session.h"

#include <gmsh.h>
#include <omp.h>

#include <cstddef>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace rbcflow {

GmshSession::GmshSession() : threads_(omp_get_max_threads()) {
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.AbortOnError", 0);
  gmsh::model::add("vessel");
}

GmshSession::~GmshSession() {
  gmsh::finalize();
  omp_set_num_threads(threads_);
}

std::string gmsh_last_error() {
  std::string error;
  gmsh::logger::getLastError(error);
  return error.empty() ? std::string("unknown gmsh error") : error;
}

TriangleMesh gmsh_triangles() {
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, true, false);
  std::vector<std::size_t> element_tags, element_nodes;
  gmsh::model::mesh::getElementsByType(2, element_tags, element_nodes);

  std::unordered_map<std::size_t, int> row;
  TriangleMesh m;
  m.points.resize(static_cast<Eigen::Index>(node_tags.size()), 3);
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    if (row.count(node_tags[i])) continue;
    const int r = static_cast<int>(row.size());
    row[node_tags[i]] = r;
    for (int d = 0; d < 3; ++d) m.points(r, d) = coords[3 * i + d];
  }
  m.points.conservativeResize(static_cast<Eigen::Index>(row.size()), 3);
  m.triangles.resize(static_cast<Eigen::Index>(element_tags.size()), 3);
  for (std::size_t t = 0; t < element_tags.size(); ++t)
    for (int a = 0; a < 3; ++a) {
      const auto it = row.find(element_nodes[3 * t + a]);
      if (it == row.end()) throw std::runtime_error("gmsh mesh refers to a node it does not list");
      m.triangles(static_cast<Eigen::Index>(t), a) = it->second;
    }
  // Drop nodes no triangle uses (geometry points, curve nodes of other dimensions).
  std::vector<int> used(m.points.rows(), -1);
  int n = 0;
  for (Eigen::Index t = 0; t < m.triangles.rows(); ++t)
    for (int a = 0; a < 3; ++a) {
      int& u = used[m.triangles(t, a)];
      if (u < 0) u = n++;
      m.triangles(t, a) = u;
    }
  TriangleMesh out;
  out.triangles = m.triangles;
  out.points.resize(n, 3);
  for (Eigen::Index i = 0; i < m.points.rows(); ++i)
    if (used[i] >= 0) out.points.row(used[i]) = m.points.row(i);
  return out;
}

}  // namespace rbcflow
