#include "libsolver/stepper/cell_proximity.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "geometry/surface/sh_surface.h"
#include "geometry/vessel/vessel_mesh.h"
#include "libsolver/wall/centroid_bins.h"

namespace rbcflow {
namespace {

// Gauss-Newton iterations of the projection: seeded at a grid node a fraction of the grid
// spacing away, within a reach of a tenth of a cell's size from the surface, it gains a factor
// ~ reach * curvature (< 0.2 for the collision threshold's reach 2 h_s) per iteration: 6 leave
// < 1e-5 of the grid spacing there, < 1e-2 at a repulsion range 0.1 against the rim of a red
// cell (curvature ~5), a distance error of the square of that.
constexpr int kProjectionIterations = 6;

// Translations of cell b's images that may come within `margin` of cell a: the minimum image
// and its neighbours along the periodic axes (a box side may be shorter than two cells). For
// a == b the unshifted cell is left out and of the images +o and -o only one is kept.
std::vector<Eigen::Vector3d> close_images(const CellView& a, const CellView& b, bool same, const Eigen::Vector3d& period,
                                          double margin) {
  const Eigen::Vector3d d = b.centre - a.centre;
  const Eigen::Vector3d base = minimum_image(d, period) - d;
  std::vector<Eigen::Vector3d> offsets{base};
  for (int k = 0; k < 3; ++k) {
    if (period[k] <= 0) continue;
    const std::size_t n = offsets.size();
    for (int s : {-1, 1})
      for (std::size_t i = 0; i < n; ++i) offsets.push_back(offsets[i] + s * period[k] * Eigen::Vector3d::Unit(k));
  }
  std::vector<Eigen::Vector3d> close;
  for (const Eigen::Vector3d& o : offsets) {
    if ((d + o).norm() >= a.radius + b.radius + margin) continue;
    if (same) {
      // o = 0 is the cell itself; keep o only when its first nonzero component is positive.
      int k = 0;
      while (k < 3 && o[k] == 0) ++k;
      if (k == 3 || o[k] < 0) continue;
    }
    close.push_back(o);
  }
  return close;
}

}  // namespace

CellView cell_view(const SHCoeffs& coeffs, const SHTransform& t) {
  CellView v;
  v.points = t.synthesize(coeffs);
  v.centre = v.points.colwise().mean().transpose();
  v.radius = (v.points.rowwise() - v.centre.transpose()).rowwise().norm().maxCoeff();
  return v;
}

void build_tree(CellView& view, const SHCoeffs& coeffs, const SHTransform& t) {
  view.mesh = SHSurface(coeffs).triangulate(t);
  view.tree = std::make_unique<TriangleAabbTree>(view.mesh);
}

// The candidates b of cell a are those whose centres lie within 2 r_max + margin of a's
// (minimum image: an image of b within r_a + r_b + margin has the minimum image within it too),
// from bins of the centres, in ascending order: the pairs of a loop over all, in its order.
Neighbourhood find_neighbours(const std::vector<CellView>& views, const Eigen::Vector3d& period, double margin) {
  const int n = static_cast<int>(views.size());
  Neighbourhood h;
  h.near.resize(n);
  std::vector<Eigen::Vector3d> centres;
  double largest_radius = 0.0;
  for (const CellView& v : views) {
    centres.push_back(v.centre);
    largest_radius = std::max(largest_radius, v.radius);
  }
  const CentroidBins bins(centres, period, 2.0 * largest_radius + margin);
  std::vector<int> candidates;
  for (int a = 0; a < n; ++a) {
    bins.candidates(views[a].centre, candidates);
    for (const int b : candidates) {
      if (b < a) continue;
      for (const Eigen::Vector3d& o : close_images(views[a], views[b], a == b, period, margin)) {
        h.near[a].push_back({b, o, h.pairs});
        h.near[b].push_back({a, -o, h.pairs});
        ++h.pairs;
      }
    }
  }
  return h;
}

std::optional<SurfaceProjection> project_within(const CellView& b, const SHCoeffs& b_coeffs, const SphGrid& grid,
                                                const Eigen::Vector3d& q, double reach) {
  if ((q - b.centre).norm() > b.radius + reach) return std::nullopt;
  const TriangleAabbTree::ClosestPoint c = b.tree->closest_point(q);
  const auto tri = b.mesh.triangles.row(c.triangle);
  const Eigen::Vector3d v0 = b.mesh.points.row(tri[0]).transpose();
  const Eigen::Vector3d n = (b.mesh.points.row(tri[1]).transpose() - v0).cross(b.mesh.points.row(tri[2]).transpose() - v0);
  const bool inside = (q - c.point).dot(n) < 0;
  // The triangulation is within its chord sag (< h_s for a resolved cell) of the surface.
  if (!inside && c.distance > reach) return std::nullopt;
  const Eigen::Vector2d angles = triangulation_seed(b.mesh, grid, c.triangle, q);
  return project_onto_surface(b_coeffs, q, angles[0], angles[1], kProjectionIterations);
}

}  // namespace rbcflow
