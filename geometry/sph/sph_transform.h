#pragma once
// Spherical-harmonic transforms of eq. (13) on a SphGrid: FFTW in longitude, Legendre tables
// in colatitude. Synthesis evaluates any mixed derivative d^a/dtheta^a d^b/dphi^b spectrally.
//
// A transform is immutable after construction and may be used from several threads at once.
#include <Eigen/Core>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "geometry/sph/legendre.h"
#include "geometry/sph/sph_coeffs.h"
#include "geometry/sph/sph_grid.h"

namespace rbcflow {

class SHTransform {
 public:
  // Band limit `order` (degrees n < order) on `grid`, with colatitude derivatives up to
  // `max_theta_derivative`. The grid must have n_phi >= 2 order - 1.
  SHTransform(int order, SphGrid grid, int max_theta_derivative = 2);
  // The paper's grid for order N: N Gauss-Legendre colatitudes x 2N longitudes.
  static SHTransform gauss(int order, int max_theta_derivative = 2);
  ~SHTransform();
  SHTransform(const SHTransform&) = delete;
  SHTransform& operator=(const SHTransform&) = delete;

  int order() const { return order_; }
  int max_theta_derivative() const { return static_cast<int>(tables_.size()) - 1; }
  const SphGrid& grid() const { return grid_; }

  // Grid values (grid().size() x k) -> coefficients of degree < out_order (0: order()).
  // Needs a Gauss grid. Exact for data band-limited to degree < order() when
  // n_theta >= order(); otherwise the discrete projection (which is how de-aliasing truncates).
  SHCoeffs analyze(const Eigen::MatrixXd& values, int out_order = 0) const;

  // d^dtheta/dtheta^dtheta d^dphi/dphi^dphi of the expansion c (c.order() <= order()) on the
  // grid, as a (grid().size() x c.components()) matrix.
  Eigen::MatrixXd synthesize(const SHCoeffs& c, int dtheta = 0, int dphi = 0) const;
  void synthesize(const SHCoeffs& c, int dtheta, int dphi, Eigen::MatrixXd& out) const;

 private:
  struct Plans;
  const Plans& plans(int components) const;

  int order_;
  SphGrid grid_;
  LegendreTables tables_;                     // tables_[k][m]: n_theta x (order - m)
  std::vector<Eigen::MatrixXd> analysis_;     // analysis_[m]: (order - m) x n_theta
  mutable std::mutex plans_mutex_;
  mutable std::map<int, std::unique_ptr<Plans>> plans_;
};

// Value of the expansion (and its derivatives) at one point (theta, phi): a row of
// c.components() numbers. O(N^2) per call; for many points on a grid use SHTransform.
Eigen::RowVectorXd sh_evaluate(const SHCoeffs& c, double theta, double phi, int dtheta = 0,
                               int dphi = 0);

// A 3-component expansion (a surface x) and its derivatives up to second order in theta and
// phi at one point, from one Legendre table: what a Newton iteration on the surface needs.
// Equal to sh_evaluate with (dtheta, dphi) = (0,0), (1,0), (0,1), (2,0), (1,1), (0,2).
struct SHJet {
  Eigen::Vector3d x, x_t, x_p, x_tt, x_tp, x_pp;
};
SHJet sh_evaluate_jet(const SHCoeffs& c, double theta, double phi);

}  // namespace rbcflow
