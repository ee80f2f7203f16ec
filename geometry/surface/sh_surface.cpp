#include "geometry/surface/sh_surface.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rbcflow {
namespace {

Eigen::VectorXd rowwise_dot(const SurfaceGeometry::Field3& a, const SurfaceGeometry::Field3& b) {
  return (a.array() * b.array()).rowwise().sum();
}

}  // namespace

SurfaceGeometry surface_geometry(const SHCoeffs& x, const SHTransform& t) {
  if (x.components() != 3) throw std::invalid_argument("surface_geometry: need 3 components");
  if (!t.grid().is_gauss()) throw std::invalid_argument("surface_geometry: need a Gauss grid");
  if (t.max_theta_derivative() < 2) {
    throw std::invalid_argument("surface_geometry: transform needs theta derivatives up to 2");
  }
  SurfaceGeometry g;
  g.x = t.synthesize(x, 0, 0);
  g.a1 = t.synthesize(x, 1, 0);
  g.a2 = t.synthesize(x, 0, 1);
  g.x11 = t.synthesize(x, 2, 0);
  g.x12 = t.synthesize(x, 1, 1);
  g.x22 = t.synthesize(x, 0, 2);

  const int np = g.size();
  g.normal.resize(np, 3);
  g.jacobian.resize(np);
  for (int p = 0; p < np; ++p) {
    const Eigen::Vector3d c = Eigen::Vector3d(g.a1.row(p)).cross(Eigen::Vector3d(g.a2.row(p)));
    g.jacobian[p] = c.norm();
    g.normal.row(p) = c / g.jacobian[p];
  }
  g.a11 = rowwise_dot(g.a1, g.a1);
  g.a12 = rowwise_dot(g.a1, g.a2);
  g.a22 = rowwise_dot(g.a2, g.a2);
  g.b11 = rowwise_dot(g.x11, g.normal);
  g.b12 = rowwise_dot(g.x12, g.normal);
  g.b22 = rowwise_dot(g.x22, g.normal);

  const SphGrid& grid = t.grid();
  g.area_weight.resize(np);
  for (int p = 0; p < np; ++p) {
    // dS = |a1 x a2| dtheta dphi = (|a1 x a2| / sin theta) d(cos theta) dphi.
    g.area_weight[p] = grid.sphere_weight(p) * g.jacobian[p] / std::sin(grid.theta()[p / grid.n_phi()]);
  }

  const Eigen::ArrayXd det = g.a11.array() * g.a22.array() - g.a12.array().square();
  const Eigen::ArrayXd inv11 = g.a22.array() / det, inv12 = -g.a12.array() / det,
                       inv22 = g.a11.array() / det;
  g.mean_curvature =
      0.5 * (inv11 * g.b11.array() + 2.0 * inv12 * g.b12.array() + inv22 * g.b22.array());
  g.gaussian_curvature = (g.b11.array() * g.b22.array() - g.b12.array().square()) / det;

  const SurfaceGeometry::Field3* second[3] = {&g.x11, &g.x12, &g.x22};
  for (int s = 0; s < 3; ++s) {
    const Eigen::ArrayXd g1 = rowwise_dot(g.a1, *second[s]).array();  // a_1 . x_,ij
    const Eigen::ArrayXd g2 = rowwise_dot(g.a2, *second[s]).array();  // a_2 . x_,ij
    g.christoffel[0][s] = inv11 * g1 + inv12 * g2;
    g.christoffel[1][s] = inv12 * g1 + inv22 * g2;
  }
  return g;
}

double surface_area(const SurfaceGeometry& g) { return g.area_weight.sum(); }

double enclosed_volume(const SurfaceGeometry& g) {
  return rowwise_dot(g.x, g.normal).dot(g.area_weight) / 3.0;
}

Eigen::Vector3d volume_centroid(const SurfaceGeometry& g) {
  // integral_V x_i dV = (1/2) integral_S x_i^2 n_i dS.
  Eigen::Vector3d m;
  for (int i = 0; i < 3; ++i) {
    m[i] = 0.5 * (g.x.col(i).array().square() * g.normal.col(i).array() * g.area_weight.array()).sum();
  }
  return m / enclosed_volume(g);
}

Eigen::Matrix3d inertia_tensor(const SurfaceGeometry& g) {
  // integral_V r_i r_j dV = (1/5) integral_S r_i r_j (r . n) dS, with r = x - centroid.
  const Eigen::Vector3d c = volume_centroid(g);
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int p = 0; p < g.size(); ++p) {
    const Eigen::Vector3d r = Eigen::Vector3d(g.x.row(p)) - c;
    const double rn = r.dot(Eigen::Vector3d(g.normal.row(p)));
    second += (rn * g.area_weight[p] / 5.0) * (r * r.transpose());
  }
  return second.trace() * Eigen::Matrix3d::Identity() - second;
}

SHSurface::SHSurface(SHCoeffs x) : x_(std::move(x)) {
  if (x_.components() != 3) throw std::invalid_argument("SHSurface: need 3 components");
}

void SHSurface::translate(const Eigen::Vector3d& shift) {
  // Pbar_0^0 = 1/sqrt(2), so a constant c has a_00 = sqrt(2) c.
  x_.values().row(0) += std::sqrt(2.0) * shift.transpose();
}

void SHSurface::rotate(const Eigen::Matrix3d& R, const Eigen::Vector3d& center) { transform(R, center); }

void SHSurface::transform(const Eigen::Matrix3d& A, const Eigen::Vector3d& center) {
  translate(-center);
  x_.values() = x_.values() * A.transpose();
  translate(center);
}

Eigen::Vector3d SHSurface::north_pole() const { return sh_evaluate(x_, 0.0, 0.0).transpose(); }
Eigen::Vector3d SHSurface::south_pole() const {
  return sh_evaluate(x_, std::numbers::pi, 0.0).transpose();
}

TriangleMesh SHSurface::triangulate(const SHTransform& t) const {
  const int nt = t.grid().n_theta(), nphi = t.grid().n_phi();
  TriangleMesh mesh;
  mesh.points.resize(t.grid().size() + 2, 3);
  mesh.points.topRows(t.grid().size()) = t.synthesize(x_);
  const int north = t.grid().size(), south = north + 1;
  mesh.points.row(north) = north_pole().transpose();
  mesh.points.row(south) = south_pole().transpose();

  mesh.triangles.resize(2 * nphi * (nt - 1) + 2 * nphi, 3);
  int k = 0;
  auto id = [nphi](int i, int j) { return i * nphi + (j % nphi); };
  for (int j = 0; j < nphi; ++j) mesh.triangles.row(k++) << north, id(0, j), id(0, j + 1);
  for (int i = 0; i + 1 < nt; ++i) {
    for (int j = 0; j < nphi; ++j) {
      mesh.triangles.row(k++) << id(i, j), id(i + 1, j), id(i, j + 1);
      mesh.triangles.row(k++) << id(i + 1, j), id(i + 1, j + 1), id(i, j + 1);
    }
  }
  for (int j = 0; j < nphi; ++j) mesh.triangles.row(k++) << south, id(nt - 1, j + 1), id(nt - 1, j);
  return mesh;
}

Eigen::Vector2d triangulation_seed(const TriangleMesh& mesh, const SphGrid& grid, int triangle, const Eigen::Vector3d& x) {
  int seed = mesh.triangles(triangle, 0);
  for (int k = 1; k < 3; ++k) {
    const int v = mesh.triangles(triangle, k);
    if ((mesh.points.row(v).transpose() - x).squaredNorm() < (mesh.points.row(seed).transpose() - x).squaredNorm()) seed = v;
  }
  if (seed == grid.size()) return {0.0, 0.0};
  if (seed == grid.size() + 1) return {std::numbers::pi, 0.0};
  return {grid.theta()[seed / grid.n_phi()], grid.phi(seed % grid.n_phi())};
}

}  // namespace rbcflow
