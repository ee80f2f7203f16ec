#include "geometry/contact/cell_overlap.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace rbcflow {
namespace {

// The surface itself (no truncation) sampled on check_order Gauss colatitudes; the longitudes
// as many as the reference's order needs.
TriangleMesh centred_mesh(const SHSurface& reference, int check_order, const Eigen::Vector3d& centroid) {
  const int n_phi = 2 * std::max(check_order, reference.order());
  TriangleMesh m = reference.triangulate(SHTransform(reference.order(), SphGrid::gauss(check_order, n_phi), 0));
  m.points.rowwise() -= centroid.transpose();
  return m;
}

// The points every test measures: the triangulation's vertices and the solver's own grid
// (Gauss, N x 2N), which lies between them. A surface bulges beyond its triangles by their
// sagitta, at a red cell's rim up to about the placement gap: tested only at the vertices, a
// grid point of a placed N = 8 cell sat 0.001 beyond the wall of a network.
Eigen::Matrix<double, Eigen::Dynamic, 3> tested_points(const SHSurface& reference, const TriangleMesh& mesh,
                                                       const Eigen::Vector3d& centroid) {
  const TriangleMesh grid = reference.triangulate(SHTransform::gauss(reference.order()));
  Eigen::Matrix<double, Eigen::Dynamic, 3> points(mesh.num_points() + grid.num_points(), 3);
  points << mesh.points, grid.points.rowwise() - centroid.transpose();
  return points;
}

// On the grid of order 2N: the integrands of the volume moments are products of three fields.
Eigen::Vector3d reference_centroid(const SHSurface& reference) {
  return volume_centroid(reference.geometry(SHTransform::gauss(2 * reference.order())));
}

// The reference's distance table (DistanceBounds): its bounding box widened by a quarter of its
// radius, nodes a 40th of the radius apart (0.035 for a red cell: a point passes without a
// query when it is 0.03 beyond the gap).
constexpr double kBoundsMargin = 0.25;
constexpr double kBoundsSpacing = 1.0 / 40.0;

}  // namespace

CellOverlap::Body::Body(const SHSurface& surface, int check_order)
    : centroid(reference_centroid(surface)),
      mesh(centred_mesh(surface, check_order, centroid)),
      points(tested_points(surface, mesh, centroid)),
      radius(points.rowwise().norm().maxCoeff()),
      tree(mesh) {
  normals.resize(mesh.num_triangles(), 3);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d p0 = mesh.points.row(mesh.triangles(t, 0)).transpose();
    normals.row(t) = (mesh.points.row(mesh.triangles(t, 1)).transpose() - p0)
                         .cross(mesh.points.row(mesh.triangles(t, 2)).transpose() - p0)
                         .transpose();
  }
}

CellOverlap::CellOverlap(const SHSurface& reference, int check_order, const Eigen::Vector3d& period,
                         const WallDistance* wall, double gap)
    : period_(period), wall_(wall), gap_(gap) {
  Body& body = bodies_.emplace_back(reference, check_order);
  body.bounds.emplace(body.mesh, body.normals, body.tree, kBoundsMargin * body.radius, kBoundsSpacing * body.radius);
}

CellOverlap::CellOverlap(const std::vector<SHSurface>& bodies, int check_order, const Eigen::Vector3d& period,
                         const WallDistance* wall, double gap)
    : period_(period), wall_(wall), gap_(gap) {
  bodies_.reserve(bodies.size());
  for (const SHSurface& s : bodies) bodies_.emplace_back(s, check_order);
}

// Every vertex of b (moved by `shift`) outside a and at least gap from a's triangles. A vertex
// found outside at distance d leaves a ball of radius d free of a's surface, so a later vertex
// within d - gap of it is outside and at least gap away too, with no query: placement runs
// thousands of these tests one after another, and most vertices are far from contact. Serial:
// a test is too short to share among threads (their start-up cost more than the test on a
// loaded machine); callers run independent tests side by side instead.
bool CellOverlap::vertices_apart(const CellPose& a, const CellPose& b, const Eigen::Vector3d& shift) const {
  const Body& body_a = bodies_[a.body];
  const auto& points_b = bodies_[b.body].points;
  const Eigen::Matrix3d to_a = a.rotation.transpose() / a.scale;
  const double reach = body_a.radius + gap_ / a.scale, gap = gap_ / a.scale;  // in a's unscaled body frame
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  double free_radius = -1.0;  // about anchor, beyond gap (none yet)
  for (Eigen::Index v = 0; v < points_b.rows(); ++v) {
    const Eigen::Vector3d x = b.rotation * (b.scale * points_b.row(v).transpose()) + b.position + shift;
    const Eigen::Vector3d y = to_a * (x - a.position);
    if (y.norm() > reach || (y - anchor).norm() <= free_radius) continue;
    if (body_a.bounds && body_a.bounds->lower(y) >= gap) continue;
    const TriangleAabbTree::ClosestPoint c = body_a.tree.closest_point(y);
    if (c.distance < gap || (y - c.point).dot(body_a.normals.row(c.triangle).transpose()) < 0) return false;
    anchor = y;
    free_radius = c.distance - gap;
  }
  return true;
}

bool CellOverlap::apart(const CellPose& a, const CellPose& b, bool same) const {
  const Eigen::Vector3d d = b.position - a.position;
  std::vector<Eigen::Vector3d> shifts{minimum_image(d, period_) - d};
  for (int k = 0; k < 3; ++k) {
    if (period_[k] <= 0) continue;
    const std::size_t n = shifts.size();
    for (int s : {-1, 1})
      for (std::size_t i = 0; i < n; ++i) shifts.push_back(shifts[i] + s * period_[k] * Eigen::Vector3d::Unit(k));
  }
  for (const Eigen::Vector3d& shift : shifts) {
    if (same && shift.isZero()) continue;
    if ((d + shift).norm() >= bodies_[a.body].radius * a.scale + bodies_[b.body].radius * b.scale + gap_) continue;
    if (!vertices_apart(a, b, shift) || !vertices_apart(b, a, -shift)) return false;
  }
  return true;
}

bool CellOverlap::inside_wall(const CellPose& a) const {
  if (!wall_) return true;
  const auto& points = bodies_[a.body].points;
  const double centre = wall_->closest(a.position).signed_distance;
  if (centre >= bodies_[a.body].radius * a.scale + gap_) return true;
  if (centre <= 0) return false;
  // As in vertices_apart: a point at signed distance s inside the lumen leaves a ball of radius s
  // free of the wall; vertices within s - gap of the last one queried (first, the centre) pass.
  Eigen::Vector3d anchor = a.position;
  double free_radius = centre - gap_;
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    const Eigen::Vector3d x = a.rotation * (a.scale * points.row(v).transpose()) + a.position;
    if ((x - anchor).norm() <= free_radius) continue;
    const double s = wall_->closest(x).signed_distance;
    if (s < gap_) return false;
    anchor = x;
    free_radius = s - gap_;
  }
  return true;
}

}  // namespace rbcflow
