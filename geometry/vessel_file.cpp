#include <gmsh.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "gmsh_session.h"
#include "mesh_check.h"
#include "vessel.h"

namespace rbcflow {

VesselMesh read_vessel(const std::string& path, const Eigen::Vector3d& period) {
  if (!std::filesystem::is_regular_file(path))
    throw std::runtime_error("wall mesh file " + path + " does not exist");
  if (std::filesystem::file_size(path) == 0)
    throw std::runtime_error("wall mesh file " + path + " is empty");
  GmshSession session;
  try {
    gmsh::option::setNumber("Geometry.Tolerance", 1e-12);
    gmsh::merge(path);
  } catch (...) {
    throw std::runtime_error("cannot read wall mesh file " + path + ": " + gmsh_last_error());
  }
  VesselMesh wall;
  wall.surface = gmsh_triangles();
  wall.period = period;
  if (wall.surface.num_triangles() == 0)
    throw std::runtime_error("wall mesh file " + path + " has no triangles");
  try {
    check_mesh(wall);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("wall mesh file ").append(path).append(": ").append(e.what()));
  }
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
