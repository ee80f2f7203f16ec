#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <string>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/sph/fftw_util.h"
#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/spme/bspline.h"
#include "libsolver/spme/spme_grid.h"

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;
using Complex = std::complex<double>;

const PeriodicBox kBox(Eigen::Vector3d(1.0, 1.5, 0.8));
const EwaldParameters kParams{6.0, 0.5, {16, 20, 12}, 6};

std::size_t mode_index(const SpmeGrid& g, int i, int j, int l) {
  return (static_cast<std::size_t>(i) * g.size(1) + j) * (g.size(2) / 2 + 1) + l;
}
Eigen::Vector3d wavevector(int i, int j, int l, const SpmeGrid& g) {
  const auto signed_m = [&](int m, int d) { return m <= g.size(d) / 2 ? m : m - g.size(d); };
  return Eigen::Vector3d(2 * pi * signed_m(i, 0) / kBox.length(0),
                         2 * pi * signed_m(j, 1) / kBox.length(1), 2 * pi * l / kBox.length(2));
}
double spline_modulus(int i, int j, int l, const SpmeGrid& g) {
  return bspline_modulus(g.order(), g.size(0))[i] * bspline_modulus(g.order(), g.size(1))[j] *
         bspline_modulus(g.order(), g.size(2))[l];
}
// This process's resident memory ("VmRSS") or its peak since the last reset ("VmHWM"), in
// bytes, from /proc/self/status; -1 where there is none.
long long status_bytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stoll(line.substr(field.size() + 1)) * 1024;
  return -1;
}
// Resets the peak to the present resident memory (Linux 4.0 on); false where it cannot.
bool reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}
}  // namespace

// The in-place transforms of 3 interleaved grids with padded rows give each component's DFT,
// as FFTW's out-of-place transform of that component alone computes it, and backward(forward(x))
// = K1 K2 K3 x at every grid point (the rows' padding is no part of the grid).
TEST(SpmeGrid, InPlaceTransformsOfInterleavedGrids) {
  const SpmeGrid grid(kBox, kParams);
  const int K1 = grid.size(0), K2 = grid.size(1), K3 = grid.size(2), n3 = K3 / 2 + 1, R = grid.row_stride();
  ASSERT_EQ(R, 2 * n3);
  const std::size_t n = grid.real_points();
  FftwBuffer<fftw_complex> data(grid.buffer_size(3));
  ASSERT_EQ(grid.buffer_size(3), 3 * grid.complex_points());
  double* real = SpmeGrid::real_part(data.data());
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> original(3 * n);  // component c of (i, j, l) at ((i K2 + j) K3 + l) 3 + c
  for (double& x : original) x = u(gen);
  for (std::size_t row = 0; row < static_cast<std::size_t>(K1) * K2; ++row)
    for (int l = 0; l < R; ++l)
      for (int c = 0; c < 3; ++c) real[(row * R + l) * 3 + c] = l < K3 ? original[(row * K3 + l) * 3 + c] : 1e300;
  grid.forward(data.data());

  double err = 0, norm = 0;
  for (int c = 0; c < 3; ++c) {
    FftwBuffer<double> one(n);
    FftwBuffer<fftw_complex> spectrum(grid.complex_points());
    for (std::size_t p = 0; p < n; ++p) one.data()[p] = original[3 * p + c];
    const fftw_plan plan = fftw_plan_dft_r2c_3d(K1, K2, K3, one.data(), spectrum.data(), FFTW_ESTIMATE);
    fftw_execute(plan);
    fftw_destroy_plan(plan);
    for (std::size_t m = 0; m < grid.complex_points(); ++m)
      for (int k = 0; k < 2; ++k) {
        err = std::max(err, std::abs(data.data()[3 * m + c][k] - spectrum.data()[m][k]));
        norm = std::max(norm, std::abs(spectrum.data()[m][k]));
      }
  }
  EXPECT_LT(err, 1e-13 * norm) << "forward against FFTW's out-of-place transform of each component";

  grid.backward(data.data());
  double back = 0;
  for (std::size_t row = 0; row < static_cast<std::size_t>(K1) * K2; ++row)
    for (int l = 0; l < K3; ++l)
      for (int c = 0; c < 3; ++c)
        back = std::max(back, std::abs(real[(row * R + l) * 3 + c] / n - original[(row * K3 + l) * 3 + c]));
  EXPECT_LT(back, 1e-14);
}

// FFTW_MEASURE plans by running candidate transforms on an array. Planned on the work array
// itself (work_array(), before the array is written), the first transforms of a grid need no
// second array of its size: the process's peak grows by one array, not two (a gigabyte of
// each for the 1,000-cell tube's grid). Transforms planned so serve any array: the round trip
// of a second work array returns K1 K2 K3 x.
TEST(SpmeGrid, MeasuredTransformsArePlannedOnTheWorkArray) {
#if defined(__SANITIZE_ADDRESS__)
  constexpr bool kResidentMemoryIsTheProgram = false;  // AddressSanitizer's shadow memory and quarantine
#else
  constexpr bool kResidentMemoryIsTheProgram = true;
#endif
  const SpmeGrid grid(kBox, EwaldParameters{6.0, 0.5, {80, 80, 80}, 6}, FftPlanning::measure);
  const long long bytes = static_cast<long long>(grid.buffer_size(3) * sizeof(fftw_complex));  // 12.6 MB
  const bool measured = kResidentMemoryIsTheProgram && reset_peak_memory() && status_bytes("VmHWM") >= 0;
  const long long before = status_bytes("VmRSS");
  {
    WorkArray data = grid.work_array(3);
    double* real = SpmeGrid::real_part(data.data());
    for (std::size_t p = 0; p < grid.buffer_size(3) * 2; ++p) real[p] = 1.0;
    grid.forward(data.data());
    grid.backward(data.data());
  }
  if (measured) {
    const long long grown = status_bytes("VmHWM") - before;
    std::printf("peak grown by %.1f MB for a work array of %.1f MB\n", grown / 1e6, bytes / 1e6);
    EXPECT_GT(grown, bytes * 9 / 10);  // the work array itself, written
    EXPECT_LT(grown, bytes * 3 / 2);   // and no second array to plan on
  } else {
    std::printf("the peak is not measured here (no /proc/self/clear_refs, or AddressSanitizer)\n");
  }

  WorkArray data = grid.work_array(3);
  const int K3 = grid.size(2), R = grid.row_stride();
  const std::size_t rows = static_cast<std::size_t>(grid.size(0)) * grid.size(1);
  double* real = SpmeGrid::real_part(data.data());
  std::mt19937 gen(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(rows * K3 * 3);  // component c of (row, l) at (row K3 + l) 3 + c
  for (double& v : x) v = u(gen);
  for (std::size_t row = 0; row < rows; ++row)
    for (int l = 0; l < K3; ++l)
      for (int c = 0; c < 3; ++c) real[(row * R + l) * 3 + c] = x[(row * K3 + l) * 3 + c];
  grid.forward(data.data());
  grid.backward(data.data());
  double err = 0;
  for (std::size_t row = 0; row < rows; ++row)
    for (int l = 0; l < K3; ++l)
      for (int c = 0; c < 3; ++c)
        err = std::max(err, std::abs(real[(row * R + l) * 3 + c] / static_cast<double>(grid.real_points()) -
                                     x[(row * K3 + l) * 3 + c]));
  std::printf("round trip of a second work array: %.2e\n", err);
  EXPECT_LT(err, 1e-14);
}

// One mode at a time: u^ = (1/V) K^F(-k) rho^ / |B|^2, zero at k = 0 and on Nyquist planes.
TEST(SpmeGrid, InfluenceFunctionPerMode) {
  const SpmeGrid grid(kBox, kParams);
  const std::size_t points = grid.complex_points();
  // No table of the spectrum: the wavenumbers and the influence function's factors per direction.
  EXPECT_LE(grid.memory_bytes(), 2 * sizeof(double) * (16 + 20 + (12 / 2 + 1)));
  FftwBuffer<fftw_complex> f(3 * points), diagonal(3 * points), off_diagonal(3 * points), u(3 * points);
  for (std::size_t i = 0; i < 3 * points; ++i) f.data()[i][0] = f.data()[i][1] = 1.0;
  const Eigen::Vector3d q(0.3, -1.0, 0.5), n(0.6, 0.0, 0.8);
  const Eigen::Matrix3d D = 0.5 * (q * n.transpose() + n * q.transpose());
  const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  for (std::size_t m = 0; m < points; ++m) {
    for (int c = 0; c < 3; ++c) {
      diagonal.data()[3 * m + c][0] = D(pairs[c][0], pairs[c][1]);
      off_diagonal.data()[3 * m + c][0] = D(pairs[c + 3][0], pairs[c + 3][1]);
      diagonal.data()[3 * m + c][1] = off_diagonal.data()[3 * m + c][1] = 0.0;
    }
  }
  grid.apply_stokeslet(f.data());
  // D in parts: the diagonal written and the off-diagonal half added, (a) as three interleaved
  // spectra, (b) one component at a time from arrays of one spectrum, (c) with the diagonal's
  // spectra turned into the velocity in place: the same numbers.
  grid.apply_stresslet(0, 3, diagonal.data(), u.data(), false);
  grid.apply_stresslet(3, 3, off_diagonal.data(), u.data(), true);
  FftwBuffer<fftw_complex> by_parts(3 * points), one(points);
  grid.apply_stresslet(0, 3, diagonal.data(), by_parts.data(), false);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t m = 0; m < points; ++m)
      for (int k = 0; k < 2; ++k) one.data()[m][k] = off_diagonal.data()[3 * m + c][k];
    grid.apply_stresslet(3 + c, 1, one.data(), by_parts.data(), true);
  }
  grid.apply_stresslet(0, 3, diagonal.data(), diagonal.data(), false);
  grid.apply_stresslet(3, 3, off_diagonal.data(), diagonal.data(), true);
  double largest = 0, parts = 0;
  for (std::size_t i = 0; i < 3 * points; ++i) {
    ASSERT_EQ(diagonal.data()[i][0], u.data()[i][0]);
    ASSERT_EQ(diagonal.data()[i][1], u.data()[i][1]);
    for (int k = 0; k < 2; ++k) {
      largest = std::max(largest, std::abs(u.data()[i][k]));
      parts = std::max(parts, std::abs(by_parts.data()[i][k] - u.data()[i][k]));
    }
  }
  EXPECT_LT(parts, 1e-15 * largest) << "the off-diagonal components one at a time";
  EXPECT_THROW(grid.apply_stresslet(4, 3, off_diagonal.data(), u.data(), true), std::invalid_argument);
  const auto at = [](FftwBuffer<fftw_complex>& b, std::size_t i) {
    return Complex(b.data()[i][0], b.data()[i][1]);
  };
  for (const auto& [i, j, l] : {std::tuple{1, 2, 3}, std::tuple{15, 0, 1}, std::tuple{3, 17, 0},
                                std::tuple{0, 0, 0}, std::tuple{8, 1, 1}, std::tuple{2, 2, 6}}) {
    const std::size_t m = mode_index(grid, i, j, l);
    const bool dropped = (i == 0 && j == 0 && l == 0) || i == 8 || l == 6;
    const Eigen::Vector3d k = wavevector(i, j, l, grid);
    const double scale = dropped ? 0.0 : 1.0 / (kBox.volume() * spline_modulus(i, j, l, grid));
    const Eigen::Vector3d s = dropped ? Eigen::Vector3d::Zero()
                                      : Eigen::Vector3d(ewald_fourier_stokeslet_apply(
                                            k, kParams.xi, Eigen::Vector3d::Ones()));
    // T^F(-k) : (q n) = -i v(k).
    const Eigen::Vector3d v =
        dropped ? Eigen::Vector3d::Zero()
                : Eigen::Vector3d(ewald_fourier_stresslet_apply(k, kParams.xi, q, n));
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(std::abs(at(f, 3 * m + c) - scale * Complex(s[c], s[c])), 0.0, 1e-13);
      EXPECT_NEAR(std::abs(at(u, 3 * m + c) - scale * Complex(0.0, -v[c])), 0.0, 1e-13);
    }
  }
}

TEST(SpmeGrid, RejectsBadParameters) {
  for (const EwaldParameters& p :
       {EwaldParameters{-1.0, 0.5, {16, 16, 16}, 6}, EwaldParameters{6.0, 0.0, {16, 16, 16}, 6},
        EwaldParameters{6.0, 0.5, {16, 15, 16}, 6}, EwaldParameters{6.0, 0.5, {16, 16, 10}, 6},
        EwaldParameters{6.0, 0.5, {32, 32, 32}, 11}})
    EXPECT_THROW(SpmeGrid(kBox, p), std::invalid_argument);
}
