#pragma once
// The periodic box [0, L1] x [0, L2] x [0, L3] of section 2 and the point data every Ewald
// routine takes: one row per point, three columns (positions, forces, normals, ...).
#include <Eigen/Core>

namespace rbcflow {

using PointField = Eigen::Matrix<double, Eigen::Dynamic, 3>;

class PeriodicBox {
 public:
  // Throws std::invalid_argument unless every side is positive and finite.
  explicit PeriodicBox(const Eigen::Vector3d& lengths);

  const Eigen::Vector3d& lengths() const { return lengths_; }
  double length(int d) const { return lengths_[d]; }
  double volume() const { return lengths_.prod(); }
  // The image of x in [0, L1) x [0, L2) x [0, L3).
  Eigen::Vector3d wrap(const Eigen::Vector3d& x) const;

 private:
  Eigen::Vector3d lengths_;
};

}  // namespace rbcflow
