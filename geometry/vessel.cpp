#include "vessel.h"

#include <gmsh.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "gmsh_session.h"
#include "mesh_check.h"

namespace rbcflow {

namespace {

void validate(const TubeSpec& s) {
  if (s.axis < 0 || s.axis > 2) throw std::invalid_argument("tube axis must be 0, 1 or 2");
  if (!(s.box.minCoeff() > 0)) throw std::invalid_argument("tube box sides must be positive");
  if (!(s.diameter > 0)) throw std::invalid_argument("tube diameter must be positive");
  if (!(s.element_size > 0) || s.element_size > s.diameter)
    throw std::invalid_argument("tube element size must be positive and below the diameter");
  for (int d = 0; d < 3; ++d)
    if (d != s.axis && s.diameter >= s.box[d])
      throw std::invalid_argument("tube diameter must be smaller than the box cross-section");
}

// Box coordinates of a point given in the frame with the tube along z: a cyclic permutation
// (orientation preserving), so that gmsh's z becomes the box axis `axis`.
int frame_axis(int axis, int k) { return (k + axis + 1) % 3; }

// Meshes the current OCC model, whose surface runs from z = 0 to z = length, with the end
// curves periodic; merges the seam, maps to box coordinates and orients the normals to the axis.
VesselMesh mesh_periodic_tube(const TubeSpec& spec) {
  const double length = spec.box[spec.axis];
  gmsh::model::occ::synchronize();
  std::vector<std::pair<int, int>> curves;
  gmsh::model::getEntities(curves, 1);
  int bottom = -1, top = -1;
  const double box_tolerance = 1e-5 * length;  // OCC pads bounding boxes by its tolerance
  for (const auto& [dim, tag] : curves) {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
    if (std::abs(z1 - z0) > 2 * box_tolerance) continue;  // the seam line
    if (std::abs(z0) <= box_tolerance) bottom = tag;
    if (std::abs(z0 - length) <= box_tolerance) top = tag;
  }
  if (bottom < 0 || top < 0) throw std::runtime_error("gmsh: tube end circles not found");
  const std::vector<double> shift{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, length, 0, 0, 0, 1};
  gmsh::model::mesh::setPeriodic(1, {top}, {bottom}, shift);
  gmsh::option::setNumber("Mesh.MeshSizeMin", spec.element_size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", spec.element_size);
  gmsh::model::mesh::generate(2);

  const double eps = 1e-9 * length;
  VesselMesh wall;
  TriangleMesh m = gmsh_triangles();
  // Merge each node of the top circle into the node of the bottom circle below it; gmsh's
  // periodic copy makes them match exactly.
  std::vector<int> target(m.points.rows());
  std::vector<int> bottoms;
  for (int i = 0; i < m.num_points(); ++i) {
    target[i] = i;
    if (std::abs(m.points(i, 2)) <= eps) bottoms.push_back(i);
  }
  const double match = 1e-12 * spec.diameter;
  for (int i = 0; i < m.num_points(); ++i) {
    if (std::abs(m.points(i, 2) - length) > eps) continue;
    target[i] = -1;
    for (int b : bottoms)
      if ((m.points.row(i).head<2>() - m.points.row(b).head<2>()).norm() <= match) target[i] = b;
    if (target[i] < 0) throw std::runtime_error("gmsh: the periodic seam of the tube does not match");
  }
  std::vector<int> row(m.points.rows(), -1);
  int n = 0;
  for (int i = 0; i < m.num_points(); ++i)
    if (target[i] == i) row[i] = n++;
  wall.surface.points.resize(n, 3);
  for (int i = 0; i < m.num_points(); ++i)
    if (row[i] >= 0)
      for (int k = 0; k < 3; ++k) wall.surface.points(row[i], frame_axis(spec.axis, k)) = m.points(i, k);
  wall.surface.triangles.resize(m.num_triangles(), 3);
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) wall.surface.triangles(t, a) = row[target[m.triangles(t, a)]];
  wall.period[spec.axis] = length;

  // Orient towards the axis (extruded and revolved surfaces come out with opposite normals).
  Eigen::Vector3d centre = 0.5 * spec.box;
  int outward = 0;
  for (int t = 0; t < wall.surface.num_triangles(); ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    Eigen::Vector3d radial = v.rowwise().mean() - centre;
    radial[spec.axis] = 0;
    if ((v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).dot(radial) > 0) ++outward;
  }
  if (2 * outward > wall.surface.num_triangles())
    wall.surface.triangles.col(1).swap(wall.surface.triangles.col(2));
  check_mesh(wall);
  return wall;
}

// Cross-section centre in the frame with the tube along z.
Eigen::Vector2d frame_centre(const TubeSpec& s) {
  return {0.5 * s.box[frame_axis(s.axis, 0)], 0.5 * s.box[frame_axis(s.axis, 1)]};
}

VesselMesh build_tube(const TubeSpec& spec) {
  const Eigen::Vector2d c = frame_centre(spec);
  const int circle = gmsh::model::occ::addCircle(c[0], c[1], 0.0, 0.5 * spec.diameter);
  std::vector<std::pair<int, int>> out;
  gmsh::model::occ::extrude({{1, circle}}, 0, 0, spec.box[spec.axis], out);
  return mesh_periodic_tube(spec);
}

VesselMesh build_constriction(const ConstrictionSpec& spec) {
  const Eigen::Vector2d c = frame_centre(spec.tube);
  const double length = spec.tube.box[spec.tube.axis];
  constexpr int n = 201;
  std::vector<int> points;
  for (int i = 0; i < n; ++i) {
    const double z = length * i / (n - 1);
    points.push_back(gmsh::model::occ::addPoint(c[0] + 0.5 * spec.diameter(z), c[1], z));
  }
  const int spline = gmsh::model::occ::addSpline(points);
  std::vector<std::pair<int, int>> out, interior;
  gmsh::model::occ::revolve({{1, spline}}, c[0], c[1], 0, 0, 0, 1, 2 * std::numbers::pi, out);
  for (int i = 1; i + 1 < n; ++i) interior.emplace_back(0, points[i]);
  gmsh::model::occ::remove(interior);
  return mesh_periodic_tube(spec.tube);
}

}  // namespace

VesselMesh tube(const TubeSpec& spec) {
  validate(spec);
  GmshSession session;
  try {
    return build_tube(spec);
  } catch (const std::exception&) {
    throw;
  } catch (...) {
    throw std::runtime_error("gmsh could not mesh the tube: " + gmsh_last_error());
  }
}

VesselMesh constriction(const ConstrictionSpec& spec) {
  validate(spec.tube);
  if (!(spec.depth >= 0 && spec.depth < spec.tube.diameter) || !(spec.width > 0))
    throw std::invalid_argument("constriction depth must be in [0, D) and width positive");
  GmshSession session;
  try {
    return build_constriction(spec);
  } catch (const std::exception&) {
    throw;
  } catch (...) {
    throw std::runtime_error("gmsh could not mesh the constriction: " + gmsh_last_error());
  }
}

double ConstrictionSpec::diameter(double z) const {
  return tube.diameter - depth * std::exp(-width * (z - centre) * (z - centre));
}

}  // namespace rbcflow
