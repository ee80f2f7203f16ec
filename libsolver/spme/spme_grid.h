#pragma once
// The geometry-independent half of smooth particle-mesh Ewald (section 5.2; Essmann et al.
// 1995; Saintillan, Darve & Shaqfeh 2005): the uniform grid, its FFTW plans and the influence
// function of the Fourier parts S^F, T^F (eq. 25, 28; docs/references.md section 2).
//
// Grid arrays interleave components and are transformed in place (FFTW manual, section 4.3.4
// "Real-data DFT Array Format"): value c of grid point (i, j, l) is at ((i K2 + j) R + l) C + c,
// R = 2 (K3/2 + 1) (each row padded by one or two points), and after the forward transform its
// spectrum's value c of (i, j, l) at ((i K2 + j) (K3/2 + 1) + l) C + c of the same array.
// Influence (r = source - target, hence the kernels at -k; ewald_kernels.h):
//   u^(k) = (1/V) K^F(-k) rho^(k) / (|B1(m1)|^2 |B2(m2)|^2 |B3(m3)|^2),  |Bd|^2 = bspline_modulus,
// with k = 0 removed and the Nyquist planes (m_d = K_d/2) dropped.
//
// Immutable after construction: one grid may serve several SpmePlans and threads. The FFTs
// run with the OpenMP thread count current at construction. Each FFTW plan is made on its
// first use, thread-safely.
//
// The grid's directions are box axes in an order, axis(0), axis(1), axis(2) (the array's
// outermost direction first): the box's own order x, y, z unless asked otherwise, and on a
// distributed grid the axis of the most grid points first, so that the slabs cut the box
// along its longest side (a tube along z: slabs across the tube, each a length of it; as many
// slabs as that axis has grid points). A relabelling of the axes changes only the order of
// the sums' terms: the kernels are isotropic (their Fourier parts depend on k through k k^T
// and |k|, taken in the box's axes).
//
// Split over ranks (a grid made with a Communicator of several ranks, in a build with FFTW's
// MPI library: distributed()), each rank holds only its slab of the grid, planes
// [first_plane(), first_plane() + planes()) of the first direction (box axis axis(0)), and
// its block of the spectrum, transposed
// (parallel/slab_fft.h). Spreading into the slab and interpolating from it then give each
// rank its part of a product; the parts sum to the whole (operators/cell_layers.h). Its
// transforms are collective: every rank makes the same products in the same order.
#include <fftw3.h>

#include <cstddef>
#include <memory>
#include <array>
#include <mutex>
#include <optional>
#include <vector>

#include "ewald_parameters.h"
#include "grid_transform.h"
#include "geometry/sph/fftw_util.h"
#include "libsolver/common/periodic_box.h"
#include "libsolver/parallel/communicator.h"
#include "libsolver/parallel/slab_fft.h"
#include "work_array_pool.h"

namespace rbcflow {

// FFTW_ESTIMATE: planned in microseconds, the same plan in every run. FFTW_MEASURE: planned by timing
// candidates (a fraction of a second for the pieces of a 10^6-point grid, grid_transform.h),
// 1.2-1.9x faster transforms (docs/performance.md), a plan that may differ from run to run and
// with it the last bits of the results.
enum class FftPlanning { estimate, measure };

class SpmeGrid {
 public:
  // Throws std::invalid_argument for invalid parameters (validate()).
  // ranks: split the grid over them when they are several and the build has FFTW's MPI
  // library (collective), else every rank holds the whole grid. work_arrays: where the work
  // arrays come from and go back to (work_array_pool.h); without one each is freed. axes: the
  // box axis of each grid direction (a permutation of 0, 1, 2), else the order above.
  SpmeGrid(const PeriodicBox& box, const EwaldParameters& parameters,
           FftPlanning planning = FftPlanning::estimate, const Communicator& ranks = {},
           std::shared_ptr<WorkArrayPool> work_arrays = nullptr,
           std::optional<std::array<int, 3>> axes = std::nullopt);
  ~SpmeGrid();
  SpmeGrid(const SpmeGrid&) = delete;
  SpmeGrid& operator=(const SpmeGrid&) = delete;

  const PeriodicBox& box() const { return box_; }
  const EwaldParameters& parameters() const { return parameters_; }
  int axis(int d) const { return axes_[d]; }                   // box axis of grid direction d
  int size(int d) const { return parameters_.grid[axes_[d]]; }  // grid points along direction d
  int order() const { return parameters_.order; }
  FftPlanning planning() const { return flags_ == FFTW_MEASURE ? FftPlanning::measure : FftPlanning::estimate; }
  std::size_t real_points() const;     // K1 K2 K3
  std::size_t complex_points() const;  // K1 K2 (K3/2 + 1)
  std::size_t memory_bytes() const;    // the influence function's factors (FFTW's plans not counted)

  // This rank's part of the grid: all of it unless distributed().
  bool distributed() const { return slab_ != nullptr; }
  int first_plane() const { return slab_ ? slab_->first_plane() : 0; }
  int planes() const { return slab_ ? slab_->planes() : size(0); }
  int row_stride() const { return 2 * (size(2) / 2 + 1); }  // R: points from row to row
  // Points of this rank's real grid, padding included: planes() x K2 x row_stride().
  std::size_t slab_points() const { return static_cast<std::size_t>(planes()) * size(1) * row_stride(); }
  // Complex numbers of an array (FftwBuffer<fftw_complex>) that holds this rank's part of
  // `components` interleaved real grids and, in place, of their spectra: 8 C bytes a grid point
  // and the rows' padding (FFTW's transposes may ask for a little more).
  std::size_t buffer_size(int components) const;
  // The real grids of such an array.
  static double* real_part(fftw_complex* data) { return reinterpret_cast<double*>(data); }
  // Such an array (uninitialised), with the transforms of `components` grids (3 or 1: forward,
  // and backward for 3) planned on it if they were not before: FFTW_MEASURE plans by running
  // candidates on an array, and planning on the product's own array before anything is
  // written to it spares a second array of its size (a gigabyte for 3 components of a
  // 162 x 162 x 1600 grid) at the first product. forward() and backward() plan on an array of
  // their own what no work array has planned. From the grid's pool, which may hand out a larger
  // array than asked for, one a product used before.
  WorkArray work_array(int components) const;

  // Forward transform in place of `components` (3 or 1) interleaved real grids to their spectra.
  void forward(fftw_complex* data, int components = 3) const;
  // Backward (unnormalised) transform in place of 3 interleaved spectra to real grids.
  void backward(fftw_complex* data) const;

  // Single layer, in place on 3 interleaved spectra: u^ = (1/V) S^F(k) f^ / |B|^2.
  void apply_stokeslet(fftw_complex* spectrum) const;
  // Double layer, u^ = (1/V) T^F(-k) : D^ / |B|^2 for the symmetric density D = (q n^T + n
  // q^T)/2, linear in D and so taken in parts: the spectra of `count` consecutive components
  // of D from `first` (in the order xx, yy, zz, xy, xz, yz), interleaved in `part`, the other
  // components zero -> 3 interleaved velocity spectra, written (add false) or added (add true).
  // `velocity` may be `part` itself when count is 3.
  void apply_stresslet(int first, int count, const fftw_complex* part, fftw_complex* velocity, bool add) const;

 private:
  PeriodicBox box_;
  EwaldParameters parameters_;
  std::array<int, 3> axes_{0, 1, 2};  // axis(d)
  std::vector<double> wavenumber_[3];  // k along axis(d) of index m_d (signed; 0 on the Nyquist plane)
  std::vector<double> damping_[3];     // exp(-c k_d^2) / |Bd(m_d)|^2 (0 on the Nyquist plane)
  double damping_c_ = 0, scale_ = 0;   // c = 1/(4 xi^2); 8 pi / V
  // The influence 8 pi H(k)/(k^2 V |B|^2) of wavevector (i, j, l) with 1/k^2 = inv_k2 (k != 0):
  // 8 pi (1/k^2 + c) exp(-c k^2) / V / |B|^2 (ewald_fourier_scale), the exponential and the
  // moduli taken direction by direction.
  double influence(int i, int j, int l, double inv_k2) const {
    return scale_ * (inv_k2 + damping_c_) * damping_[0][i] * damping_[1][j] * damping_[2][l];
  }
  // The wavevector of indices (i, j, l) in the box's axes.
  std::array<double, 3> wavevector(int i, int j, int l) const {
    std::array<double, 3> k;
    k[axes_[0]] = wavenumber_[0][i];
    k[axes_[1]] = wavenumber_[1][j];
    k[axes_[2]] = wavenumber_[2][l];
    return k;
  }
  struct LazyPlan {
    std::once_flag made;
    std::unique_ptr<GridTransform> transform;
  };
  // The transform, planned on `on` (overwritten) or, when null, on an array of its own if not
  // planned yet.
  const GridTransform& plan(LazyPlan& p, int components, bool forward, fftw_complex* on) const;
  // Calls f(m, i, j, l) for every wavevector (i, j, l) of this rank's spectrum, m its index
  // there (spectra interleave their components: component c of m at C m + c); parallel.
  template <class F>
  void for_each_wavevector(F&& f) const;

  unsigned flags_;
  mutable LazyPlan forward3_, forward1_, backward3_;
  std::unique_ptr<SlabFft> slab_;  // distributed(): this rank's slab's transforms
  std::shared_ptr<WorkArrayPool> work_arrays_;
};

}  // namespace rbcflow
