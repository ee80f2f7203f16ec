#pragma once
// Random point data shared by the Ewald tests.
#include <random>

#include "libsolver/common/periodic_box.h"

namespace rbcflow::test {

// n points uniform in [0, L1) x [0, L2) x [0, L3).
inline PointField random_points(int n, const Eigen::Vector3d& box, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointField x(n, 3);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) x(i, d) = box[d] * u(gen);
  return x;
}

// n vectors with independent standard normal components.
inline PointField random_vectors(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  PointField f(n, 3);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) f(i, d) = g(gen);
  return f;
}

inline PointField random_unit_vectors(int n, unsigned seed) {
  return random_vectors(n, seed).rowwise().normalized();
}

// sqrt(mean over rows of |a - b|^2).
inline double rms_difference(const PointField& a, const PointField& b) {
  return std::sqrt((a - b).squaredNorm() / static_cast<double>(a.rows()));
}

}  // namespace rbcflow::test
