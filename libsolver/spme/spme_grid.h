#pragma once
// The geometry-independent half of smooth particle-mesh Ewald (section 5.2; Essmann et al.
// 1995; Saintillan, Darve & Shaqfeh 2005): the uniform grid, its FFTW plans and the influence
// function of the Fourier parts S^F, T^F (eq. 25, 28; REFERENCES.md section 2).
//
// Grid arrays interleave components: value c of grid point (i, j, l) is at
// ((i K2 + j) K3 + l) C + c, spectra likewise with K3/2 + 1 in place of K3 (FFTW r2c layout).
// Influence (r = source - target, hence the kernels at -k; ewald_kernels.h):
//   u^(k) = (1/V) K^F(-k) rho^(k) / (|B1(m1)|^2 |B2(m2)|^2 |B3(m3)|^2),  |Bd|^2 = bspline_modulus,
// with k = 0 removed and the Nyquist planes (m_d = K_d/2) dropped.
//
// Immutable after construction: one grid may serve several SpmePlans and threads. The FFTs
// run with the OpenMP thread count current at construction.
#include <fftw3.h>

#include <cstddef>
#include <vector>

#include "ewald_parameters.h"
#include "periodic_box.h"

namespace rbcflow {

enum class FftPlanning { estimate, measure };  // FFTW_ESTIMATE (fast to build) or FFTW_MEASURE

class SpmeGrid {
 public:
  // Throws std::invalid_argument for invalid parameters (validate()).
  SpmeGrid(const PeriodicBox& box, const EwaldParameters& parameters,
           FftPlanning planning = FftPlanning::estimate);
  ~SpmeGrid();
  SpmeGrid(const SpmeGrid&) = delete;
  SpmeGrid& operator=(const SpmeGrid&) = delete;

  const PeriodicBox& box() const { return box_; }
  const EwaldParameters& parameters() const { return parameters_; }
  int size(int d) const { return parameters_.grid[d]; }
  int order() const { return parameters_.order; }
  std::size_t real_points() const;     // K1 K2 K3
  std::size_t complex_points() const;  // K1 K2 (K3/2 + 1)

  // Forward transform of `components` (3 or 6) interleaved real grids (arrays from fftw_malloc).
  void forward(int components, double* real, fftw_complex* spectrum) const;
  // Backward (unnormalised) transform of 3 interleaved spectra; destroys `spectrum`.
  void backward(fftw_complex* spectrum, double* real) const;

  // Single layer, in place on 3 interleaved spectra: u^ = (1/V) S^F(k) f^ / |B|^2.
  void apply_stokeslet(fftw_complex* spectrum) const;
  // Double layer: 6 interleaved spectra of the symmetric density D = (q n^T + n q^T)/2 in the
  // order xx, yy, zz, xy, xz, yz -> 3 interleaved velocity spectra, u^ = (1/V) T^F(-k) : D^ /
  // |B|^2.
  void apply_stresslet(const fftw_complex* density, fftw_complex* velocity) const;

 private:
  PeriodicBox box_;
  EwaldParameters parameters_;
  std::vector<double> influence_;      // 8 pi H(k)/(k^2 V |B|^2) per complex grid point
  std::vector<double> wavenumber_[3];  // k_d of index m_d (signed; 0 on the Nyquist plane)
  fftw_plan forward3_ = nullptr, forward6_ = nullptr, backward3_ = nullptr;
};

}  // namespace rbcflow
