#include "near_targets.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "geometry/cgal/aabb_tree.h"
#include "geometry/surface/sh_surface.h"
#include "geometry/surface/surface_projection.h"

namespace rbcflow {
namespace {

// The target x0 with its patch centred at the projection's foot point.
void add_target(NearTargets& out, const Eigen::Vector3d& x0, const SurfaceProjection& proj, int row) {
  QuadratureTarget t;
  t.x = x0;
  t.theta = proj.theta;
  t.phi = proj.phi;
  t.distance = proj.distance;
  out.targets.push_back(t);
  out.rows.push_back(row);
}

}  // namespace

NearTargets find_near_targets(const CellQuadratureGeometry& cell, const Eigen::MatrixXd& points,
                              const std::optional<PeriodicBox>& box, int skip_begin, int skip_end) {
  NearTargets out;
  const SourceNodes& nodes = cell.nodes();
  const double near = cell.near_distance();
  const Eigen::Vector3d lo = nodes.x.colwise().minCoeff(), hi = nodes.x.colwise().maxCoeff();
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const SphGrid& grid = cell.grids().n_grid->grid();
  // The projection's seed: the vertex nearest the closest point of the grid triangulation,
  // from an AABB tree built when the first point comes within the bounding box.
  TriangleMesh mesh;
  std::unique_ptr<TriangleAabbTree> tree;
  for (int r = 0; r < points.rows(); ++r) {
    if (r >= skip_begin && r < skip_end) continue;
    Eigen::Vector3d x0 = points.row(r).transpose();
    if (box) {
      const Eigen::Vector3d L = box->lengths();
      x0 -= (L.array() * ((x0 - centre).array() / L.array()).round()).matrix();
    }
    if (((x0 - lo).array() < -near).any() || ((x0 - hi).array() > near).any()) continue;
    if (!tree) {
      mesh = SHSurface(cell.coeffs()).triangulate(*cell.grids().n_grid);
      tree = std::make_unique<TriangleAabbTree>(mesh);
    }
    const TriangleAabbTree::ClosestPoint closest = tree->closest_point(x0);
    if (closest.distance >= near + cell.mesh_size()) continue;  // the chords lie within h of the surface
    const Eigen::Vector2d seed = triangulation_seed(mesh, grid, closest.triangle, x0);
    const SurfaceProjection proj = project_onto_surface(cell.coeffs(), x0, seed[0], seed[1]);
    if (proj.distance >= near) continue;
    add_target(out, x0, proj, r);
  }
  return out;
}

NearTargets find_self_near_targets(const CellQuadratureGeometry& cell, int row_offset) {
  NearTargets out;
  const SourceNodes& nodes = cell.nodes();
  const SphGrid& grid = cell.grids().n_grid->grid();
  const double separation = std::min(std::numbers::pi, kSelfNearAngle * cell.patch_radius());
  if (separation >= std::numbers::pi) return out;  // patches too wide to keep apart (N < 9 at factor 2)
  const double cos_separation = std::cos(separation), near = cell.near_distance();
  auto direction = [](double theta, double phi) {
    return Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  const int n = grid.size();
  Eigen::MatrixXd u(n, 3);
  for (int p = 0; p < n; ++p) u.row(p) = direction(grid.theta()[p / grid.n_phi()], grid.phi(p % grid.n_phi()));
  for (int t = 0; t < n; ++t) {
    // The nearest node beyond the separation seeds the projection onto that part.
    int seed = -1;
    double closest = near + cell.mesh_size();  // the nodes lie within h of the surface's foot points
    for (int q = 0; q < n; ++q) {
      if (u.row(t).dot(u.row(q)) >= cos_separation) continue;
      const double d = (nodes.x.row(t) - nodes.x.row(q)).norm();
      if (d < closest) closest = d, seed = q;
    }
    if (seed < 0) continue;
    const Eigen::Vector3d x0 = nodes.x.row(t).transpose();
    const SurfaceProjection proj =
        project_onto_surface(cell.coeffs(), x0, grid.theta()[seed / grid.n_phi()], grid.phi(seed % grid.n_phi()));
    if (!proj.converged || proj.distance >= near) continue;
    if (u.row(t).dot(direction(proj.theta, proj.phi)) >= cos_separation) continue;  // slid back towards the node
    add_target(out, x0, proj, row_offset + t);
  }
  return out;
}

}  // namespace rbcflow
