#include "spme_grid.h"

#include <omp.h>

#include <algorithm>
#include <complex>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

#include "bspline.h"
#include "geometry/sph/fftw_util.h"
#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/common/memory_report.h"

namespace rbcflow {
namespace {

using Complex = std::complex<double>;

void check_components(int components, const char* where) {
  if (components != 3 && components != 1)
    throw std::invalid_argument(std::string(where) + ": 3 or 1 interleaved grids, not " + std::to_string(components));
}

}  // namespace

SpmeGrid::SpmeGrid(const PeriodicBox& box, const EwaldParameters& parameters, FftPlanning planning,
                   const Communicator& ranks, std::shared_ptr<WorkArrayPool> work_arrays,
                   std::optional<std::array<int, 3>> axes)
    : box_(box), parameters_(parameters), work_arrays_(std::move(work_arrays)) {
  validate(parameters, box);
  const bool split = ranks.size() > 1 && SlabFft::available();
  if (axes) {
    std::array<int, 3> sorted = *axes;
    std::sort(sorted.begin(), sorted.end());
    if (sorted != std::array<int, 3>{0, 1, 2})
      throw std::invalid_argument("SpmeGrid: the grid's axes must be a permutation of 0, 1, 2, not " +
                                  std::to_string((*axes)[0]) + ", " + std::to_string((*axes)[1]) + ", " +
                                  std::to_string((*axes)[2]));
    axes_ = *axes;
  } else if (split) {
    // The axis of the most grid points first (the first of equals), the others in their order.
    const std::array<int, 3>& g = parameters.grid;
    const int first = static_cast<int>(std::max_element(g.begin(), g.end()) - g.begin());
    axes_ = {first, first == 0 ? 1 : 0, first == 2 ? 1 : 2};
  }
  const std::array<int, 3> K{size(0), size(1), size(2)};  // by grid direction
  flags_ = planning == FftPlanning::measure ? FFTW_MEASURE : FFTW_ESTIMATE;
  if (split) slab_ = std::make_unique<SlabFft>(ranks, K, flags_, omp_get_max_threads());

  // Wavenumbers and B-spline moduli per direction; the Nyquist index gets k = 0 and is dropped.
  std::vector<double> modulus[3];
  for (int d = 0; d < 3; ++d) {
    const int n = d == 2 ? K[d] / 2 + 1 : K[d];
    wavenumber_[d].resize(n);
    for (int m = 0; m < n; ++m) {
      const int signed_m = m < K[d] / 2 ? m : (m == K[d] / 2 ? 0 : m - K[d]);
      wavenumber_[d][m] = 2.0 * std::numbers::pi * signed_m / box.length(axes_[d]);
    }
    modulus[d] = bspline_modulus(parameters.order, K[d]);
  }
  // The influence function 8 pi (1/k^2 + c) exp(-c k^2) / (V |B1|^2 |B2|^2 |B3|^2), c = 1/(4 xi^2)
  // (ewald_fourier_scale), is separable but for its first factor: its per-direction factors
  // exp(-c k_d^2) / |Bd(m_d)|^2 are kept and multiplied per wavevector in the products, instead of
  // a table of the whole spectrum (8 bytes a point: 0.17 GB for the 162 x 162 x 1600 grid of the
  // thousand cells' double layer).
  damping_c_ = 0.25 / (parameters.xi * parameters.xi);
  scale_ = 8.0 * std::numbers::pi / box.volume();
  for (int d = 0; d < 3; ++d) {
    damping_[d].assign(wavenumber_[d].size(), 0.0);
    for (std::size_t m = 0; m < damping_[d].size(); ++m) {
      if (static_cast<int>(m) == K[d] / 2) continue;  // the Nyquist plane is dropped
      const double k = wavenumber_[d][m];
      damping_[d][m] = std::exp(-damping_c_ * k * k) / modulus[d][m];
    }
  }
}

template <class F>
void SpmeGrid::for_each_wavevector(F&& f) const {
  // Serial layout (i, j, l); a slab's spectrum is transposed: (j - first_row, i, l).
  const bool transposed = slab_ != nullptr;
  const int n_outer = transposed ? slab_->rows() : size(0), n_middle = transposed ? size(0) : size(1);
  const int first_row = transposed ? slab_->first_row() : 0, n3 = size(2) / 2 + 1;
#pragma omp parallel for schedule(static)
  for (int o = 0; o < n_outer; ++o)
    for (int mid = 0; mid < n_middle; ++mid) {
      const int i = transposed ? mid : o, j = transposed ? first_row + o : mid;
      const std::size_t row = (static_cast<std::size_t>(o) * n_middle + mid) * n3;
      for (int l = 0; l < n3; ++l) f(row + l, i, j, l);
    }
}

SpmeGrid::~SpmeGrid() = default;

const GridTransform& SpmeGrid::plan(LazyPlan& p, int components, bool forward, fftw_complex* on) const {
  std::call_once(p.made, [&] {
    FftwBuffer<fftw_complex> own(on ? 0 : components * complex_points());
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    p.transform = std::make_unique<GridTransform>(std::array<int, 3>{size(0), size(1), size(2)}, components, forward,
                                                  flags_, on ? on : own.data());
  });
  return *p.transform;
}

std::size_t SpmeGrid::real_points() const {
  return static_cast<std::size_t>(size(0)) * size(1) * size(2);
}

std::size_t SpmeGrid::complex_points() const {
  return static_cast<std::size_t>(size(0)) * size(1) * (size(2) / 2 + 1);
}

std::size_t SpmeGrid::buffer_size(int components) const {
  return slab_ ? slab_->buffer_size(components) : components * complex_points();
}

WorkArray SpmeGrid::work_array(int components) const {
  check_components(components, "SpmeGrid::work_array");
  WorkArray data(work_arrays_ ? work_arrays_->take(buffer_size(components)) : FftwBuffer<fftw_complex>(buffer_size(components)),
                 work_arrays_.get());
  if (slab_) {
    slab_->plan_on(data.data(), components);
  } else {
    plan(components == 3 ? forward3_ : forward1_, components, true, data.data());
    if (components == 3) plan(backward3_, 3, false, data.data());
  }
  return data;
}

void SpmeGrid::forward(fftw_complex* data, int components) const {
  check_components(components, "SpmeGrid::forward");
  if (slab_) return slab_->forward(data, components);
  plan(components == 3 ? forward3_ : forward1_, components, true, nullptr).execute(data);
}

void SpmeGrid::backward(fftw_complex* data) const {
  if (slab_) return slab_->backward(data);
  plan(backward3_, 3, false, nullptr).execute(data);
}

void SpmeGrid::apply_stokeslet(fftw_complex* spectrum) const {
  Complex* f = reinterpret_cast<Complex*>(spectrum);
  for_each_wavevector([&](std::size_t m, int i, int j, int l) {
    Complex* fm = f + 3 * m;
    const auto [k0, k1, k2] = wavevector(i, j, l);
    const double k_squared = k0 * k0 + k1 * k1 + k2 * k2;
    const double s = k_squared == 0.0 ? 0.0 : influence(i, j, l, 1.0 / k_squared);
    if (s == 0.0) {
      fm[0] = fm[1] = fm[2] = 0.0;
      return;
    }
    // S^F(k) f = s (f - k (k.f)/k^2)
    const double inv_k2 = 1.0 / k_squared;
    const Complex kf = (k0 * fm[0] + k1 * fm[1] + k2 * fm[2]) * inv_k2;
    fm[0] = s * (fm[0] - k0 * kf);
    fm[1] = s * (fm[1] - k1 * kf);
    fm[2] = s * (fm[2] - k2 * kf);
  });
}

void SpmeGrid::apply_stresslet(int first, int count, const fftw_complex* part, fftw_complex* velocity, bool add) const {
  if (first < 0 || count < 1 || first + count > 6)
    throw std::invalid_argument("SpmeGrid::apply_stresslet: components " + std::to_string(first) + " to " +
                                std::to_string(first + count - 1) + " of 6");
  const Complex* D = reinterpret_cast<const Complex*>(part);
  Complex* u = reinterpret_cast<Complex*>(velocity);
  for_each_wavevector([&](std::size_t m, int i, int j, int l) {
    // The six components, those not given zero (read before `u` is written: it may alias).
    const Complex zero(0.0, 0.0);
    Complex d[6] = {zero, zero, zero, zero, zero, zero};
    for (int c = 0; c < count; ++c) d[first + c] = D[count * m + c];
    Complex* um = u + 3 * m;
    const auto [k0, k1, k2] = wavevector(i, j, l);
    const double k_squared = k0 * k0 + k1 * k1 + k2 * k2;
    const double inv_k2 = k_squared == 0.0 ? 0.0 : 1.0 / k_squared;
    const double s = k_squared == 0.0 ? 0.0 : influence(i, j, l, inv_k2);
    Complex v[3] = {zero, zero, zero};
    if (s != 0.0) {
      // T^F(-k) : D = -i s [2 D k + k tr D - 2 k (k.D.k)/k^2] (ewald_fourier_stresslet_apply).
      const Complex dk0 = d[0] * k0 + d[3] * k1 + d[4] * k2;
      const Complex dk1 = d[3] * k0 + d[1] * k1 + d[5] * k2;
      const Complex dk2 = d[4] * k0 + d[5] * k1 + d[2] * k2;
      const Complex scalar = d[0] + d[1] + d[2] - 2.0 * (k0 * dk0 + k1 * dk1 + k2 * dk2) * inv_k2;
      const auto times_minus_is = [s](Complex z) { return Complex(s * z.imag(), -s * z.real()); };
      v[0] = times_minus_is(2.0 * dk0 + k0 * scalar);
      v[1] = times_minus_is(2.0 * dk1 + k1 * scalar);
      v[2] = times_minus_is(2.0 * dk2 + k2 * scalar);
    }
    for (int c = 0; c < 3; ++c) um[c] = add ? um[c] + v[c] : v[c];
  });
}

std::size_t SpmeGrid::memory_bytes() const {
  std::size_t bytes = 0;
  for (int d = 0; d < 3; ++d) bytes += heap_bytes(wavenumber_[d]) + heap_bytes(damping_[d]);
  return bytes;
}

}  // namespace rbcflow
