#pragma once
// The geometry-independent half of smooth particle-mesh Ewald (section 5.2; Essmann et al.
// 1995; Saintillan, Darve & Shaqfeh 2005): the uniform grid, its FFTW plans and the influence
// function of the Fourier parts S^F, T^F (eq. 25, 28; docs/references.md section 2).
//
// Grid arrays interleave components: value c of grid point (i, j, l) is at
// ((i K2 + j) K3 + l) C + c, spectra likewise with K3/2 + 1 in place of K3 (FFTW r2c layout).
// Influence (r = source - target, hence the kernels at -k; ewald_kernels.h):
//   u^(k) = (1/V) K^F(-k) rho^(k) / (|B1(m1)|^2 |B2(m2)|^2 |B3(m3)|^2),  |Bd|^2 = bspline_modulus,
// with k = 0 removed and the Nyquist planes (m_d = K_d/2) dropped.
//
// Immutable after construction: one grid may serve several SpmePlans and threads. The FFTs
// run with the OpenMP thread count current at construction. Each FFTW plan is made on its
// first use (a Stokeslet grid never plans the 6-component transform), thread-safely.
#include <fftw3.h>

#include <cstddef>
#include <mutex>
#include <vector>

#include "ewald_parameters.h"
#include "libsolver/common/periodic_box.h"

namespace rbcflow {

// FFTW_ESTIMATE: planned in microseconds, the same plan in every run. FFTW_MEASURE: planned by timing
// candidates (seconds for a 10^6-point grid), 1.2-1.9x faster transforms (docs/performance.md),
// a plan that may differ from run to run and with it the last bits of the results.
enum class FftPlanning { estimate, measure };

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
  FftPlanning planning() const { return flags_ == FFTW_MEASURE ? FftPlanning::measure : FftPlanning::estimate; }
  std::size_t real_points() const;     // K1 K2 K3
  std::size_t complex_points() const;  // K1 K2 (K3/2 + 1)
  std::size_t memory_bytes() const;    // influence function and wavenumbers (FFTW's plans not counted)

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
  struct LazyPlan {
    std::once_flag made;
    fftw_plan plan = nullptr;
  };
  fftw_plan plan(LazyPlan& p, int components, bool forward) const;

  unsigned flags_;
  int threads_;
  mutable LazyPlan forward3_, forward6_, backward3_;
};

}  // namespace rbcflow
