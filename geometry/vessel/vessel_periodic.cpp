#include "geometry/vessel/vessel_periodic.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"

namespace rbcflow {

int frame_axis(int axis, int k) { return (k + axis + 1) % 3; }

Eigen::Vector2d frame_centre(const TubeSpec& s) {
  return {0.5 * s.box[frame_axis(s.axis, 0)], 0.5 * s.box[frame_axis(s.axis, 1)]};
}

void validate_tube(const TubeSpec& s) {
  if (s.axis < 0 || s.axis > 2) throw std::invalid_argument("tube axis must be 0, 1 or 2");
  if (!(s.box.minCoeff() > 0)) throw std::invalid_argument("tube box sides must be positive");
  if (!(s.diameter > 0)) throw std::invalid_argument("tube diameter must be positive");
  if (!(s.element_size > 0) || s.element_size > s.diameter)
    throw std::invalid_argument("tube element size must be positive and below the diameter");
  for (int d = 0; d < 3; ++d)
    if (d != s.axis && s.diameter >= s.box[d])
      throw std::invalid_argument("tube diameter must be smaller than the box cross-section");
}

namespace {

struct Box {
  double x0, y0, z0, x1, y1, z1;
};

Box bounding_box(int dim, int tag) {
  Box b{};
  gmsh::model::getBoundingBox(dim, tag, b.x0, b.y0, b.z0, b.x1, b.y1, b.z1);
  return b;
}

// Pairs each end curve in z = length with the one in z = 0 below it, and makes it its periodic copy.
void set_periodic_ends(double length, double lateral) {
  std::vector<std::pair<int, int>> curves;
  gmsh::model::getEntities(curves, 1);
  const double tolerance = 1e-5 * length;  // OCC pads bounding boxes by its tolerance
  std::vector<std::pair<int, Box>> bottom, top;
  for (const auto& [dim, tag] : curves) {
    const Box b = bounding_box(dim, tag);
    if (std::abs(b.z1 - b.z0) > 2 * tolerance) continue;
    if (std::abs(b.z0) <= tolerance) bottom.emplace_back(tag, b);
    if (std::abs(b.z0 - length) <= tolerance) top.emplace_back(tag, b);
  }
  if (bottom.empty() || bottom.size() != top.size())
    throw std::runtime_error("the vessel's ends at the two box faces do not match (" +
                             std::to_string(bottom.size()) + " and " + std::to_string(top.size()) +
                             " end curves)");
  const std::vector<double> shift{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, length, 0, 0, 0, 1};
  for (const auto& [t, tb] : top) {
    int match = -1;
    for (const auto& [b, bb] : bottom)
      if (std::abs(tb.x0 - bb.x0) + std::abs(tb.x1 - bb.x1) + std::abs(tb.y0 - bb.y0) + std::abs(tb.y1 - bb.y1) <=
          1e-6 * lateral)
        match = b;
    if (match < 0) throw std::runtime_error("an end curve of the vessel has no periodic copy on the other box face");
    gmsh::model::mesh::setPeriodic(1, {t}, {match}, shift);
  }
}

// A CAD curve much shorter than the element size (where fillets meet) would be one edge of its
// length between triangles of size h: slivers. Near such curves the mesh size falls to the
// shortest one's length (at least h / 10), growing back to h over 4 h (a gmsh Distance +
// Threshold field);
// degenerate curves (a sphere's pole, no length) are left alone. Returns the smallest size.
double size_short_curves(double element_size) {
  std::vector<std::pair<int, int>> curves;
  gmsh::model::getEntities(curves, 1);
  double smallest = element_size;
  std::vector<double> short_curves;
  for (const auto& [dim, tag] : curves) {
    double length = 0;
    gmsh::model::occ::getMass(dim, tag, length);
    if (!(length < 0.5 * element_size) || length < 1e-6 * element_size) continue;
    short_curves.push_back(tag);
    smallest = std::min(smallest, std::max(length, 0.1 * element_size));
  }
  if (short_curves.empty()) return element_size;
  namespace field = gmsh::model::mesh::field;
  const int distance = field::add("Distance");
  field::setNumbers(distance, "CurvesList", short_curves);
  field::setNumber(distance, "Sampling", 20);
  const int threshold = field::add("Threshold");
  field::setNumber(threshold, "InField", distance);
  field::setNumber(threshold, "SizeMin", smallest);
  field::setNumber(threshold, "SizeMax", element_size);
  field::setNumber(threshold, "DistMin", smallest);
  field::setNumber(threshold, "DistMax", 4 * element_size);
  field::setAsBackgroundMesh(threshold);
  return smallest;
}

}  // namespace

void keep_only_surfaces(const std::vector<std::pair<int, int>>& surfaces) {
  namespace occ = gmsh::model::occ;
  occ::synchronize();
  std::vector<std::pair<int, int>> volumes, faces, curves, wall_curves;
  gmsh::model::getEntities(volumes, 3);
  occ::remove(volumes);
  gmsh::model::getEntities(faces, 2);
  for (const auto& f : faces)
    if (std::find(surfaces.begin(), surfaces.end(), f) == surfaces.end()) occ::remove({f});
  occ::synchronize();
  gmsh::model::getBoundary(surfaces, wall_curves, false, false, false);
  gmsh::model::getEntities(curves, 1);
  for (const auto& c : curves)
    if (std::find(wall_curves.begin(), wall_curves.end(), c) == wall_curves.end()) occ::remove({c});
  occ::synchronize();
}

std::vector<std::pair<int, int>> without_end_caps(const std::vector<std::pair<int, int>>& faces, double length) {
  const double tolerance = 1e-5 * length;  // OCC pads bounding boxes by its tolerance
  std::vector<std::pair<int, int>> wall;
  for (const auto& [dim, tag] : faces) {
    const Box b = bounding_box(dim, tag);
    const bool cap = b.z1 - b.z0 < 2 * tolerance && (std::abs(b.z0) <= tolerance || std::abs(b.z1 - length) <= tolerance);
    if (!cap) wall.emplace_back(dim, tag);
  }
  return wall;
}

VesselMesh mesh_periodic_wall(int axis, const Eigen::Vector3d& box, double element_size, double shift,
                              bool grade_short_curves) {
  const double length = box[axis];
  const double lateral = std::max(box[frame_axis(axis, 0)], box[frame_axis(axis, 1)]);
  gmsh::model::occ::synchronize();
  set_periodic_ends(length, lateral);
  gmsh::option::setNumber("Mesh.MeshSizeMin", grade_short_curves ? size_short_curves(element_size) : element_size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", element_size);
  gmsh::model::mesh::generate(2);

  const double eps = 1e-9 * length;
  TriangleMesh m = gmsh_triangles();
  // Merge each node of the far end into the node of the near end below it; gmsh's periodic
  // copy makes them match exactly.
  std::vector<int> target(m.points.rows());
  std::vector<int> bottoms;
  for (int i = 0; i < m.num_points(); ++i) {
    target[i] = i;
    if (std::abs(m.points(i, 2)) <= eps) bottoms.push_back(i);
  }
  const double match = 1e-12 * lateral;
  for (int i = 0; i < m.num_points(); ++i) {
    if (std::abs(m.points(i, 2) - length) > eps) continue;
    target[i] = -1;
    for (int b : bottoms)
      if ((m.points.row(i).head<2>() - m.points.row(b).head<2>()).norm() <= match) target[i] = b;
    if (target[i] < 0) throw std::runtime_error("gmsh: the periodic seam of the vessel does not match");
  }
  std::vector<int> row(m.points.rows(), -1);
  int n = 0;
  for (int i = 0; i < m.num_points(); ++i)
    if (target[i] == i) row[i] = n++;
  VesselMesh wall;
  wall.surface.points.resize(n, 3);
  for (int i = 0; i < m.num_points(); ++i) {
    if (row[i] < 0) continue;
    Eigen::Vector3d x = m.points.row(i).transpose();
    if (shift != 0.0) {
      x[2] = std::fmod(x[2] + shift, length);
      if (x[2] < 0) x[2] += length;
    }
    for (int k = 0; k < 3; ++k) wall.surface.points(row[i], frame_axis(axis, k)) = x[k];
  }
  wall.surface.triangles.resize(m.num_triangles(), 3);
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) wall.surface.triangles(t, a) = row[target[m.triangles(t, a)]];
  wall.period[axis] = length;
  orient_into_lumen(wall);
  check_mesh(wall);
  return wall;
}

}  // namespace rbcflow
