#pragma once
// A closed cell surface x(theta, phi) given by the spherical-harmonic coefficients of its
// three Cartesian components (section 3), and its differential geometry on a Gauss grid.
//
// Conventions: a1 = dx/dtheta, a2 = dx/dphi, n = a1 x a2 / |a1 x a2| points outward for a
// surface parametrised like the unit sphere; b_ij = x_,ij . n (eq. 17). The mean curvature is
// H = b^alpha_alpha / 2, so a sphere of radius r has H = -1/r (b = -P/r, section 3) and
// Gaussian curvature K = det(b^alpha_beta) = 1/r^2.
#include <Eigen/Core>
#include <array>

#include "geometry/sph/sph_coeffs.h"
#include "geometry/sph/sph_transform.h"
#include "geometry/surface/triangle_mesh.h"

namespace rbcflow {

struct SurfaceGeometry {
  using Field3 = Eigen::Matrix<double, Eigen::Dynamic, 3>;
  Field3 x, a1, a2, normal;       // points, tangents (16), outward unit normal
  Field3 x11, x12, x22;           // second derivatives x_theta theta, x_theta phi, x_phi phi
  Eigen::VectorXd a11, a12, a22;  // first fundamental form (17)
  Eigen::VectorXd b11, b12, b22;  // second fundamental form (17)
  Eigen::VectorXd jacobian;       // |a1 x a2| = dS / (dtheta dphi)
  Eigen::VectorXd area_weight;    // quadrature weight of each point: integral f dS = sum f w
  Eigen::VectorXd mean_curvature, gaussian_curvature;
  // christoffel[k][s]: Gamma^(k+1)_ij with s = 0, 1, 2 for ij = 11, 12, 22.
  std::array<std::array<Eigen::VectorXd, 3>, 2> christoffel;

  int size() const { return static_cast<int>(x.rows()); }
};

// Geometry of the surface with coefficients `x` (3 components, order <= t.order()) on the
// Gauss grid of `t`, which needs theta derivatives up to 2.
SurfaceGeometry surface_geometry(const SHCoeffs& x, const SHTransform& t);

// Integral properties from the geometry (the surface is closed and outward oriented).
double surface_area(const SurfaceGeometry& g);
double enclosed_volume(const SurfaceGeometry& g);
Eigen::Vector3d volume_centroid(const SurfaceGeometry& g);
// Inertia tensor of the enclosed volume (unit density) about its centroid:
// I = integral (|r|^2 I - r r^T) dV.
Eigen::Matrix3d inertia_tensor(const SurfaceGeometry& g);

class SHSurface {
 public:
  SHSurface() = default;
  explicit SHSurface(SHCoeffs x);

  int order() const { return x_.order(); }
  const SHCoeffs& coeffs() const { return x_; }
  SHCoeffs& coeffs() { return x_; }

  SurfaceGeometry geometry(const SHTransform& t) const { return surface_geometry(x_, t); }

  void translate(const Eigen::Vector3d& shift);
  // x -> R (x - center) + center.
  void rotate(const Eigen::Matrix3d& R, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());
  // x -> A (x - center) + center for any linear map A (exact on the coefficients: the
  // coordinates are linear in them). det A = 1 keeps the enclosed volume.
  void transform(const Eigen::Matrix3d& A, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

  // Points at the poles (theta = 0 and pi).
  Eigen::Vector3d north_pole() const;
  Eigen::Vector3d south_pole() const;

  // The grid of `t` triangulated, the two poles added to close the surface; outward triangles.
  TriangleMesh triangulate(const SHTransform& t) const;

 private:
  SHCoeffs x_;
};

// A seed for project_onto_surface from a closest point on SHSurface::triangulate's mesh of
// `grid`: the (theta, phi) of the vertex of `triangle` nearest x (the poles are the last two
// vertices).
Eigen::Vector2d triangulation_seed(const TriangleMesh& mesh, const SphGrid& grid, int triangle, const Eigen::Vector3d& x);

}  // namespace rbcflow
