#include "geometry/contact/radial_profile.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "geometry/cgal/aabb_tree.h"

namespace rbcflow {

namespace {

constexpr int kRingsPerBin = 2;

}  // namespace

std::vector<double> radial_volume_fraction(TriangleMesh surfaces, const Eigen::VectorXi& component,
                                           const RadialProfileSpec& spec) {
  if (surfaces.num_triangles() == 0) throw std::invalid_argument("radial profile: no surfaces");
  if (component.size() != surfaces.num_points() || component.minCoeff() < 0)
    throw std::invalid_argument("radial profile: one component index per point is needed");
  if (!(spec.radius > 0 && spec.period > 0 && spec.spacing > 0) || spec.bins < 1 || spec.axis < 0 || spec.axis > 2)
    throw std::invalid_argument("radial profile: the tube, the bins and the spacing must be positive");
  const int a = spec.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  {  // each surface by whole periods into the period
    const int n = component.maxCoeff() + 1;
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(n), count = Eigen::VectorXd::Zero(n);
    for (int p = 0; p < surfaces.num_points(); ++p) {
      sum[component[p]] += surfaces.points(p, a);
      count[component[p]] += 1;
    }
    for (int p = 0; p < surfaces.num_points(); ++p)
      surfaces.points(p, a) -= spec.period * std::floor(sum[component[p]] / count[component[p]] / spec.period);
  }
  const TriangleAabbTree tree(surfaces);
  Eigen::MatrixX3d normals(surfaces.num_triangles(), 3);
  for (int t = 0; t < surfaces.num_triangles(); ++t) {
    const Eigen::Vector3d p0 = surfaces.points.row(surfaces.triangles(t, 0));
    normals.row(t) = (Eigen::Vector3d(surfaces.points.row(surfaces.triangles(t, 1))) - p0)
                         .cross(Eigen::Vector3d(surfaces.points.row(surfaces.triangles(t, 2))) - p0)
                         .transpose();
  }
  auto inside_once = [&](const Eigen::Vector3d& x) {
    const TriangleAabbTree::ClosestPoint c = tree.closest_point(x);
    return (x - c.point).dot(normals.row(c.triangle).transpose()) < 0;
  };
  const Eigen::Vector3d along = Eigen::Vector3d::Unit(a) * spec.period;
  const int slices = std::max(1, static_cast<int>(std::ceil(spec.period / spec.spacing)));
  const double width = spec.radius / spec.bins;
  std::vector<double> fraction(spec.bins, 0.0);
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < spec.bins; ++i) {
    const double r0 = i * width, r1 = (i + 1) * width;
    double sum = 0.0;  // over the bin's rings, each of equal area
    for (int k = 0; k < kRingsPerBin; ++k) {
      const double r = std::sqrt(r0 * r0 + (k + 0.5) / kRingsPerBin * (r1 * r1 - r0 * r0));
      const int around = std::max(8, static_cast<int>(std::ceil(2 * std::numbers::pi * r / spec.spacing)));
      long in = 0;
      for (int j = 0; j < around; ++j) {
        const double phi = 2 * std::numbers::pi * (j + 0.5) / around;
        for (int s = 0; s < slices; ++s) {
          Eigen::Vector3d x = spec.axis_point;
          x[u] += r * std::cos(phi);
          x[v] += r * std::sin(phi);
          x[a] = (s + 0.5) * spec.period / slices;
          if (inside_once(x) || inside_once(x + along) || inside_once(x - along)) ++in;
        }
      }
      sum += static_cast<double>(in) / (static_cast<double>(around) * slices);
    }
    fraction[i] = sum / kRingsPerBin;
  }
  return fraction;
}

}  // namespace rbcflow
