#pragma once
// Which wall triangles may be near a point: their centroids binned on a uniform grid of cells
// at least `radius` wide (periodic along the wall's periods), so that the near-field search of
// near_field.h visits the 27 bins around a target instead of every triangle.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace rbcflow {

class CentroidBins {
 public:
  // `period`: 0 along a non-periodic axis. radius > 0.
  CentroidBins(const std::vector<Eigen::Vector3d>& centroids, const Eigen::Vector3d& period, double radius);

  // Every triangle whose centroid is within `radius` of x (minimum image), and possibly some
  // farther ones, in ascending order (the order of a loop over all triangles): `out` is
  // overwritten.
  void candidates(const Eigen::Vector3d& x, std::vector<int>& out) const;

 private:
  // Bin index along axis d of coordinate v (wrapped on periodic axes; may be out of range on
  // the others).
  long bin_of(int d, double v) const;

  Eigen::Vector3d period_, origin_, width_;
  std::array<long, 3> count_{};
  std::vector<int> start_;      // bin b holds indices_[start_[b], start_[b + 1])
  std::vector<int> indices_;    // triangles, ascending within each bin
};

}  // namespace rbcflow
