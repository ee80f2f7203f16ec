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

// One cell's membrane: its stress-free reference (metric and curvature on the M grid,
// computed once) and its parameters.
class Membrane {
 public:
  Membrane(const SHSurface& reference, std::shared_ptr<const CellGrids> grids,
           MembraneParameters params);

  // Traction and membrane diagnostics for the deformed surface x (order N coefficients).
  MembraneState compute(const SHCoeffs& x) const;
  // Only the elastic energy (cheaper; for diagnostics and tests).
  double elastic_energy(const SHCoeffs& x) const;

  const CellGrids& grids() const { return *grids_; }
  const MembraneParameters& parameters() const { return params_; }
  const SHSurface& reference() const { return reference_; }

 private:
  struct Kinematics;
  Kinematics kinematics(const SurfaceGeometry& g) const;

  SHSurface reference_;
  std::shared_ptr<const CellGrids> grids_;
  MembraneParameters params_;
  // Reference quantities on the M grid: contravariant metric A^{ab} and mixed curvature B^a_b.
  Eigen::VectorXd ref_inv11_, ref_inv12_, ref_inv22_, ref_det_;
  Eigen::VectorXd ref_b11_, ref_b12_, ref_b21_, ref_b22_;
};

}  // namespace rbcflow
