#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vessel/gmsh_session.h"
#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"
#include "geometry/vessel/vessel.h"

namespace rbcflow {

namespace {

// Merges nodes that coincide modulo the period (a periodic seam written on both box faces),
// within 1e-10 of the mesh's extent, as check_mesh's duplicate test; drops the far copies.
void merge_periodic_copies(VesselMesh& wall) {
  if (wall.period.isZero()) return;
  TriangleMesh& m = wall.surface;
  const double tolerance = 1e-10 * (m.points.colwise().maxCoeff() - m.points.colwise().minCoeff()).norm();
  int d = 0;
  while (!(wall.period[d] > 0)) ++d;
  const double l = wall.period[d];
  auto key = [&](int i) { return m.points(i, d) - l * std::floor(m.points(i, d) / l + tolerance / l); };
  std::vector<int> order(m.points.rows()), target(m.points.rows());
  for (int i = 0; i < m.num_points(); ++i) order[i] = target[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  const int n = m.num_points();
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n && key(order[b]) - key(order[a]) <= tolerance; ++b) {
      const int i = order[a], j = order[b];
      const Eigen::Vector3d gap = (m.points.row(j) - m.points.row(i)).transpose();
      if (gap.norm() > tolerance && minimum_image(gap, wall.period).norm() <= tolerance)
        target[std::max(i, j)] = target[std::min(i, j)];
    }
  std::vector<int> row(n, -1);
  int kept = 0;
  for (int i = 0; i < n; ++i)
    if (target[i] == i) row[i] = kept++;
  if (kept == n) return;
  TriangleMesh merged;
  merged.points.resize(kept, 3);
  for (int i = 0; i < n; ++i)
    if (row[i] >= 0) merged.points.row(row[i]) = m.points.row(i);
  merged.triangles = m.triangles;
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) merged.triangles(t, a) = row[target[m.triangles(t, a)]];
  m = merged;
}

}  // namespace

VesselMesh read_vessel(const std::string& path, const Eigen::Vector3d& period, double scale) {
  if (!std::filesystem::is_regular_file(path))
    throw std::runtime_error("wall mesh file " + path + " does not exist");
  if (std::filesystem::file_size(path) == 0)
    throw std::runtime_error("wall mesh file " + path + " is empty");
  if (!(scale > 0)) throw std::invalid_argument("wall mesh scale must be positive");
  VesselMesh wall;
  {
    GmshSession session;
    try {
      gmsh::option::setNumber("Geometry.Tolerance", 1e-12);
      gmsh::merge(path);
      wall.surface = gmsh_triangles();
    } catch (...) {
      throw std::runtime_error("cannot read wall mesh file " + path + ": " + gmsh_last_error());
    }
  }
  wall.surface.points *= scale;
  wall.period = period;
  if (wall.surface.num_triangles() == 0)
    throw std::runtime_error("wall mesh file " + path + " has no triangles");
  try {
    merge_periodic_copies(wall);
    check_mesh(wall);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("wall mesh file ").append(path).append(": ").append(e.what()));
  }
  // Consistent (check_mesh) but possibly outward: the other convention, not a defect.
  if (lumen_flux(wall) > 0) wall.surface.triangles.col(1).swap(wall.surface.triangles.col(2));
  return wall;
}

void write_vessel(const VesselMesh& wall, const std::string& path) {
  GmshSession session;
  const TriangleMesh& m = wall.surface;
  const int surface = gmsh::model::addDiscreteEntity(2);
  std::vector<std::size_t> node_tags(m.num_points()), element_tags(m.num_triangles()),
      element_nodes(3 * m.num_triangles());
  std::vector<double> coords(3 * m.num_points());
  for (int i = 0; i < m.num_points(); ++i) {
    node_tags[i] = static_cast<std::size_t>(i + 1);
    for (int k = 0; k < 3; ++k) coords[3 * i + k] = m.points(i, k);
  }
  for (int t = 0; t < m.num_triangles(); ++t) {
    element_tags[t] = static_cast<std::size_t>(t + 1);
    for (int a = 0; a < 3; ++a) element_nodes[3 * t + a] = static_cast<std::size_t>(m.triangles(t, a) + 1);
  }
  gmsh::model::mesh::addNodes(2, surface, node_tags, coords);
  gmsh::model::mesh::addElementsByType(surface, 2, element_tags, element_nodes);
  try {
    gmsh::write(path);
  } catch (...) {
    throw std::runtime_error("cannot write wall mesh file " + path + ": " + gmsh_last_error());
  }
  if (!std::filesystem::is_regular_file(path))
    throw std::runtime_error("cannot write wall mesh file " + path);
}

}  // namespace rbcflow
