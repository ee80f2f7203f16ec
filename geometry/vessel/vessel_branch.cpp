#include "geometry/vessel/vessel_branch.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/sph/gauss_legendre.h"

namespace rbcflow {

int nearest_branch(const std::vector<VesselBranch>& branches, const Eigen::Vector3d& x, const Eigen::Vector3d& period) {
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(branches.size()); ++i) {
    const VesselBranch& b = branches[i];
    const Eigen::Vector3d d = b.to - b.from;
    for (int a = 0; a < 3; ++a) {
      for (int k = -1; k <= 1; ++k) {
        if (k != 0 && period[a] == 0) continue;
        Eigen::Vector3d y = x;
        y[a] += k * period[a];
        const double t = std::clamp((y - b.from).dot(d) / d.squaredNorm(), 0.0, 1.0);
        const double distance = (y - b.from - t * d).norm() - b.radius;
        if (distance < best_distance) {
          best_distance = distance;
          best = i;
        }
      }
    }
  }
  return best;
}

SectionQuadrature section_quadrature(const VesselBranch& branch, int radial, int angular) {
  SectionQuadrature q;
  q.normal = branch.direction();
  // Two unit vectors across the normal.
  const Eigen::Vector3d e1 = q.normal.unitOrthogonal(), e2 = q.normal.cross(e1);
  const GaussLegendreRule rule = gauss_legendre(radial);
  q.points.resize(radial * angular, 3);
  q.weights.resize(radial * angular);
  const double r = branch.radius;
  for (int i = 0; i < radial; ++i) {
    const double rho = 0.5 * r * (1 + std::cos(rule.theta[i]));  // x = cos(theta) in [-1, 1] -> [0, r]
    const double w = 0.5 * r * rule.weights[i] * rho * 2 * std::numbers::pi / angular;
    for (int j = 0; j < angular; ++j) {
      const double phi = 2 * std::numbers::pi * j / angular;
      q.points.row(i * angular + j) = branch.centre() + rho * (std::cos(phi) * e1 + std::sin(phi) * e2);
      q.weights[i * angular + j] = w;
    }
  }
  return q;
}

std::vector<SectionQuadrature> candidate_sections(const VesselBranch& branch, int count) {
  const double a = branch.clear_from, b = branch.clear_to;
  if (count < 2 || b <= a) {
    VesselBranch mid = branch;
    const double t = 0.5 * (a + b);
    mid.from = branch.from + (t - 0.5) * (branch.to - branch.from);
    mid.to = branch.to + (t - 0.5) * (branch.to - branch.from);
    return {section_quadrature(mid)};
  }
  std::vector<SectionQuadrature> sections;
  for (int k = 0; k < count; ++k) {
    const double t = a + (b - a) * k / (count - 1);
    VesselBranch at = branch;  // the same line, its middle moved to t
    at.from = branch.from + (t - 0.5) * (branch.to - branch.from);
    at.to = branch.to + (t - 0.5) * (branch.to - branch.from);
    sections.push_back(section_quadrature(at));
  }
  return sections;
}

}  // namespace rbcflow
