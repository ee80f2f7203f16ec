#include "geometry/surface/inertia_ellipsoid.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace rbcflow {

InertiaEllipsoid inertia_ellipsoid(const SurfaceGeometry& g) {
  const double volume = enclosed_volume(g);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia_tensor(g));
  const Eigen::Vector3d I = eig.eigenvalues();  // ascending: the largest moment is the shortest axis
  InertiaEllipsoid e;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    e.semi_axes[2 - i] = std::sqrt(std::max(0.0, 2.5 / volume * (I[j] + I[k] - I[i])));
    e.axes.col(2 - i) = eig.eigenvectors().col(i);
  }
  return e;
}

}  // namespace rbcflow
