// GridTransform (the SPME grids' 3-D transforms planned as rows, planes and column blocks)
// against the discrete Fourier transform summed directly, and against FFTW's own 3-D plan.
#include "libsolver/spme/grid_transform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <mutex>
#include <numbers>
#include <vector>

#include "geometry/sph/fftw_util.h"

namespace rbcflow {
namespace {

using Complex = std::complex<double>;

struct Grids {
  std::array<int, 3> n;
  int C;
  int n3() const { return n[2] / 2 + 1; }
  std::size_t complex_size() const { return static_cast<std::size_t>(n[0]) * n[1] * n3() * C; }
  // Offset in doubles of value c of real point (i, j, l) (padded rows), and in complex numbers
  // of value c of mode (i, j, l).
  std::size_t real_at(int i, int j, int l, int c) const {
    return ((static_cast<std::size_t>(i) * n[1] + j) * 2 * n3() + l) * C + c;
  }
  std::size_t mode_at(int i, int j, int l, int c) const {
    return ((static_cast<std::size_t>(i) * n[1] + j) * n3() + l) * C + c;
  }
};

// Reproducible values on the real points (the rows' padding left zero).
void fill(const Grids& g, double* real) {
  std::fill(real, real + 2 * g.complex_size(), 0.0);
  for (int i = 0; i < g.n[0]; ++i)
    for (int j = 0; j < g.n[1]; ++j)
      for (int l = 0; l < g.n[2]; ++l)
        for (int c = 0; c < g.C; ++c) real[g.real_at(i, j, l, c)] = std::sin(1.0 + 0.37 * g.real_at(i, j, l, c)) + 0.1 * c;
}

std::unique_ptr<GridTransform> make(const Grids& g, bool forward, unsigned flags, fftw_complex* on) {
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  return std::make_unique<GridTransform>(g.n, g.C, forward, flags, on);
}

TEST(GridTransform, ForwardIsTheDirectDiscreteFourierTransform) {
  // Odd and even sizes, one and three interleaved grids (rows of an odd number of complex
  // numbers take the unaligned plans).
  for (const Grids g : {Grids{{5, 6, 7}, 3}, Grids{{4, 6, 8}, 1}, Grids{{6, 5, 9}, 1}}) {
    FftwBuffer<fftw_complex> data(g.complex_size());
    double* real = reinterpret_cast<double*>(data.data());
    const auto forward = make(g, true, FFTW_MEASURE, data.data());
    fill(g, real);
    const std::vector<double> input(real, real + 2 * g.complex_size());
    forward->execute(data.data());
    double worst = 0, largest = 0;
    for (int a = 0; a < g.n[0]; ++a)
      for (int b = 0; b < g.n[1]; ++b)
        for (int m = 0; m < g.n3(); ++m)
          for (int c = 0; c < g.C; ++c) {
            Complex sum = 0;  // sum of x exp(-2 pi i (a i/K1 + b j/K2 + m l/K3))
            for (int i = 0; i < g.n[0]; ++i)
              for (int j = 0; j < g.n[1]; ++j)
                for (int l = 0; l < g.n[2]; ++l) {
                  const double phase = -2 * std::numbers::pi *
                                       (double(a * i) / g.n[0] + double(b * j) / g.n[1] + double(m * l) / g.n[2]);
                  sum += input[g.real_at(i, j, l, c)] * std::polar(1.0, phase);
                }
            const fftw_complex& got = data.data()[g.mode_at(a, b, m, c)];
            worst = std::max(worst, std::abs(Complex(got[0], got[1]) - sum));
            largest = std::max(largest, std::abs(sum));
          }
    // Rounding of a direct sum of K1 K2 K3 <= 270 terms of size <= 1.1: ~1e-13 of the largest mode.
    EXPECT_LT(worst, 1e-12 * largest) << g.n[0] << "x" << g.n[1] << "x" << g.n[2] << ", C = " << g.C;
  }
}

TEST(GridTransform, AgreesWithFftwsWholeTransformBothWays) {
  for (const unsigned flags : {FFTW_ESTIMATE, FFTW_MEASURE})
    for (const Grids g : {Grids{{20, 18, 41}, 3}, Grids{{24, 24, 48}, 1}, Grids{{21, 15, 30}, 3}}) {
      FftwBuffer<fftw_complex> data(g.complex_size()), reference(g.complex_size());
      const auto forward = make(g, true, flags, data.data());
      const auto backward = make(g, false, flags, data.data());
      double* real = reinterpret_cast<double*>(data.data());
      double* reference_real = reinterpret_cast<double*>(reference.data());
      fftw_plan whole_forward, whole_backward;
      {
        std::lock_guard<std::mutex> lock(fftw_planner_mutex());
        const int dims[3] = {g.n[0], g.n[1], g.n[2]};
        const int real_rows[3] = {g.n[0], g.n[1], 2 * g.n3()}, complex_rows[3] = {g.n[0], g.n[1], g.n3()};
        whole_forward = fftw_plan_many_dft_r2c(3, dims, g.C, reference_real, real_rows, g.C, 1, reference.data(),
                                               complex_rows, g.C, 1, FFTW_ESTIMATE);
        whole_backward = fftw_plan_many_dft_c2r(3, dims, g.C, reference.data(), complex_rows, g.C, 1,
                                                reference_real, real_rows, g.C, 1, FFTW_ESTIMATE);
      }
      fill(g, real);
      fill(g, reference_real);
      forward->execute(data.data());
      fftw_execute(whole_forward);
      double worst = 0, largest = 0;
      for (std::size_t k = 0; k < g.complex_size(); ++k) {
        const Complex got(data.data()[k][0], data.data()[k][1]), want(reference.data()[k][0], reference.data()[k][1]);
        worst = std::max(worst, std::abs(got - want));
        largest = std::max(largest, std::abs(want));
      }
      EXPECT_LT(worst, 1e-13 * largest) << "forward " << g.n[0] << "x" << g.n[1] << "x" << g.n[2] << ", C = " << g.C;
      backward->execute(data.data());
      fftw_execute(whole_backward);
      worst = largest = 0;
      for (int i = 0; i < g.n[0]; ++i)
        for (int j = 0; j < g.n[1]; ++j)
          for (int l = 0; l < g.n[2]; ++l)
            for (int c = 0; c < g.C; ++c) {
              const std::size_t at = g.real_at(i, j, l, c);
              worst = std::max(worst, std::abs(real[at] - reference_real[at]));
              largest = std::max(largest, std::abs(reference_real[at]));
            }
      // Both are K1 K2 K3 times the input (unnormalised): the round trip's rounding, ~1e-15 of it.
      EXPECT_LT(worst, 1e-13 * largest) << "backward " << g.n[0] << "x" << g.n[1] << "x" << g.n[2] << ", C = " << g.C;
      std::lock_guard<std::mutex> lock(fftw_planner_mutex());
      fftw_destroy_plan(whole_forward);
      fftw_destroy_plan(whole_backward);
    }
}

}  // namespace
}  // namespace rbcflow
