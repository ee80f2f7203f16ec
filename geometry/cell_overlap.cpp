#include "cell_overlap.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
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

// On the grid of order 2N: the integrands of the volume moments are products of three fields.
Eigen::Vector3d reference_centroid(const SHSurface& reference) {
  return volume_centroid(reference.geometry(SHTransform::gauss(2 * reference.order())));
}

}  // namespace

CellOverlap::CellOverlap(const SHSurface& reference, int check_order, const Eigen::Vector3d& period,
                         const WallDistance* wall, double gap)
    : period_(period),
      wall_(wall),
      gap_(gap),
      centroid_(reference_centroid(reference)),
      mesh_(centred_mesh(reference, check_order, centroid_)),
      radius_(mesh_.points.rowwise().norm().maxCoeff()),
      tree_(mesh_) {
  normals_.resize(mesh_.num_triangles(), 3);
  for (int t = 0; t < mesh_.num_triangles(); ++t) {
    const Eigen::Vector3d p0 = mesh_.points.row(mesh_.triangles(t, 0)).transpose();
    normals_.row(t) = (mesh_.points.row(mesh_.triangles(t, 1)).transpose() - p0)
                          .cross(mesh_.points.row(mesh_.triangles(t, 2)).transpose() - p0)
                          .transpose();
  }
}

// Every vertex of b (moved by `shift`) outside a and at least gap from a's triangles. The
// vertices are checked by all threads (placement runs thousands of these tests one after
// another); the first failure stops the others' remaining checks.
bool CellOverlap::vertices_apart(const CellPose& a, const CellPose& b, const Eigen::Vector3d& shift) const {
  const Eigen::Matrix3d to_a = a.rotation.transpose() / a.scale;
  const double reach = radius_ + gap_ / a.scale;
  std::atomic<bool> apart{true};
#pragma omp parallel for schedule(static)
  for (int v = 0; v < mesh_.num_points(); ++v) {
    if (!apart.load(std::memory_order_relaxed)) continue;
    const Eigen::Vector3d x = b.rotation * (b.scale * mesh_.points.row(v).transpose()) + b.position + shift;
    const Eigen::Vector3d y = to_a * (x - a.position);  // in a's unscaled body frame
    if (y.norm() > reach) continue;
    const TriangleAabbTree::ClosestPoint c = tree_.closest_point(y);
    if (c.distance * a.scale < gap_ || (y - c.point).dot(normals_.row(c.triangle).transpose()) < 0)
      apart.store(false, std::memory_order_relaxed);
  }
  return apart;
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
    if ((d + shift).norm() >= radius_ * (a.scale + b.scale) + gap_) continue;
    if (!vertices_apart(a, b, shift) || !vertices_apart(b, a, -shift)) return false;
  }
  return true;
}

bool CellOverlap::inside_wall(const CellPose& a) const {
  if (!wall_) return true;
  const double centre = wall_->closest(a.position).signed_distance;
  if (centre >= radius_ * a.scale + gap_) return true;
  if (centre <= 0) return false;
  std::atomic<bool> inside{true};  // threads as in vertices_apart
#pragma omp parallel for schedule(static)
  for (int v = 0; v < mesh_.num_points(); ++v) {
    if (!inside.load(std::memory_order_relaxed)) continue;
    const Eigen::Vector3d x = a.rotation * (a.scale * mesh_.points.row(v).transpose()) + a.position;
    if (wall_->closest(x).signed_distance < gap_) inside.store(false, std::memory_order_relaxed);
  }
  return inside;
}

}  // namespace rbcflow
