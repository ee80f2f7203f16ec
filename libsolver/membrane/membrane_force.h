#pragma once
// The hydrodynamic traction that holds a deformed membrane in equilibrium, eq. (22)-(23):
//   f = -div_s T,  T = N^{ab} a_a (x) a_b + Q^a a_a (x) n,  Q = P div_s(M^{ab} a_a (x) a_b),
// with the in-plane tension N from a MembraneLaw, the bending moment (21)
// M^a_b = -E_B (b^a_b - b^{aR}_b), and surface divergences computed spectrally
// (geometry/surface/surface_divergence.h). This f is the traction jump of eq. (6): the membrane's own
// elastic load on the fluid is -f. An inflated sphere has f . n = +2 tau / r > 0 (the membrane
// pulls inward; the fluid must push outward), and the virtual work is dE = integral f . dX dA.
//
// De-aliasing (section 10): every nonlinear operation is done on the M x 2M grid from the
// order-N coefficients (zero-padded), and f is truncated back to degrees n < N.
#include <Eigen/Core>
#include <memory>

#include "geometry/surface/cell_grids.h"
#include "geometry/surface/sh_surface.h"
#include "libsolver/membrane/membrane_law.h"

namespace rbcflow {

struct MembraneParameters {
  std::shared_ptr<const MembraneLaw> law;
  double bending_modulus = 0.0;  // E_B of eq. (21)
};

// What a force evaluation returns. Grid fields are on the N x 2N grid (the cell's own grid),
// filtered to degrees n < N.
struct MembraneState {
  SHCoeffs traction;                  // f, degrees n < N (3 components)
  Eigen::MatrixXd traction_grid;      // f on the N grid (points x 3)
  Eigen::VectorXd dilatation;         // J_S = l1 l2 on the N grid
  Eigen::MatrixXd principal_tension;  // in-plane Cauchy tensions (tau_1 >= tau_2), points x 2
  double elastic_energy = 0.0;        // integral W dA_ref + (E_B / 2) integral |b - b^R|^2 dA
};

// The stress-free reference's contravariant metric a^{ab}, |a| = det a_{ab} and mixed curvature
// b^a_b = a^{ac} b_cb on the M grid. They belong to the surface and its parametrisation, not to
// where it lies: a rigid motion of the shape (SHSurface::rotate, translate: the coefficients
// move, the parameter sphere stays) leaves them unchanged, so the cells of a run, rotated
// copies of one reference shape, share one (8 values a point of the M grid: 0.3 MB a cell at
// N = 16, M = 48).
struct RestMetrics {
  RestMetrics(const SHSurface& reference, const CellGrids& grids);
  Eigen::VectorXd inv11, inv12, inv22, det;
  Eigen::VectorXd b11, b12, b21, b22;
  std::size_t memory_bytes() const;
};

// One cell's membrane: its stress-free reference (metric and curvature on the M grid) and its
// parameters.
class Membrane {
 public:
  // rest: the metrics of `reference` or of a shape it is a rigid motion of (shared by the
  // cells placed as copies of one shape); computed from `reference` when null.
  Membrane(const SHSurface& reference, std::shared_ptr<const CellGrids> grids, MembraneParameters params,
           std::shared_ptr<const RestMetrics> rest = nullptr);

  // Traction and membrane diagnostics for the deformed surface x (order N coefficients).
  MembraneState compute(const SHCoeffs& x) const;
  // Only the elastic energy (cheaper; for diagnostics and tests).
  double elastic_energy(const SHCoeffs& x) const;

  const CellGrids& grids() const { return *grids_; }
  const MembraneParameters& parameters() const { return params_; }
  const SHSurface& reference() const { return reference_; }
  const std::shared_ptr<const RestMetrics>& rest_metrics() const { return rest_; }

 private:
  struct Kinematics;
  Kinematics kinematics(const SurfaceGeometry& g) const;

  SHSurface reference_;
  std::shared_ptr<const CellGrids> grids_;
  MembraneParameters params_;
  std::shared_ptr<const RestMetrics> rest_;
};

}  // namespace rbcflow
