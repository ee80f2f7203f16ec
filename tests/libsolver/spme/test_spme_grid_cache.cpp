#include "libsolver/spme/spme_grid_cache.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "geometry/sph/fftw_util.h"

using namespace rbcflow;

// One grid per (kernel, tolerance, box, counts), with the parameters a fresh choice gives.
TEST(SpmeGridCache, SameKeySameGridOtherKeyOtherGrid) {
  SpmeGridCache cache;
  const PeriodicBox box(Eigen::Vector3d(4.0, 5.0, 6.0));
  const auto a = cache.grid(EwaldKernel::stokeslet, 1e-6, box, 1000);
  EXPECT_EQ(cache.grid(EwaldKernel::stokeslet, 1e-6, box, 1000), a);
  EXPECT_NE(cache.grid(EwaldKernel::stresslet, 1e-6, box, 1000), a);
  EXPECT_NE(cache.grid(EwaldKernel::stokeslet, 1e-6, box, 1000, 50), a);
  EXPECT_NE(cache.grid(EwaldKernel::stokeslet, 1e-5, box, 1000), a);
  const EwaldParameters fresh = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, 1000).parameters;
  EXPECT_EQ(a->parameters().xi, fresh.xi);
  EXPECT_EQ(a->parameters().grid, fresh.grid);
  EXPECT_EQ(a->parameters().order, fresh.order);
  EXPECT_EQ(ewald_grid(nullptr, EwaldKernel::stokeslet, 1e-6, box, 1000)->parameters().xi, fresh.xi);
}

// Grids kept for a run are planned with FFTW_MEASURE from kMeasuredGridPoints up (planning
// happens on the first transform, so asking costs nothing here).
TEST(SpmeGridCache, LargeGridsAreMeasured) {
  SpmeGridCache cache;
  const PeriodicBox small(Eigen::Vector3d(4.0, 5.0, 6.0)), large(Eigen::Vector3d(10.5, 10.5, 21.0));
  const auto a = cache.grid(EwaldKernel::stokeslet, 1e-6, small, 1000);
  const auto b = cache.grid(EwaldKernel::stokeslet, 1e-8, large, 20000);
  ASSERT_LT(a->real_points(), kMeasuredGridPoints);
  ASSERT_GE(b->real_points(), kMeasuredGridPoints);
  EXPECT_EQ(a->planning(), FftPlanning::estimate);
  EXPECT_EQ(b->planning(), FftPlanning::measure);
  EXPECT_EQ(ewald_grid(nullptr, EwaldKernel::stokeslet, 1e-8, large, 20000)->planning(), FftPlanning::estimate);
}

// A measured plan computes the same transforms as an estimated one, to rounding: forward and
// backward, 3 components, on random grids.
TEST(SpmeGrid, MeasuredAndEstimatedPlansAgree) {
  const PeriodicBox box(Eigen::Vector3d(3.0, 3.0, 6.0));
  const EwaldParameters p = choose_ewald_parameters(EwaldKernel::stresslet, 1e-6, box, 2000).parameters;
  const SpmeGrid measured(box, p, FftPlanning::measure), estimated(box, p, FftPlanning::estimate);
  const std::size_t nc = measured.buffer_size(3);
  ASSERT_EQ(estimated.buffer_size(3), nc);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  FftwBuffer<fftw_complex> s1(nc), s2(nc);
  for (std::size_t i = 0; i < nc; ++i)
    for (int k = 0; k < 2; ++k) s1.data()[i][k] = s2.data()[i][k] = u(rng);  // the rows' padding too
  measured.forward(s1.data());
  estimated.forward(s2.data());
  double diff = 0, norm = 0;
  for (std::size_t i = 0; i < nc; ++i)
    for (int k = 0; k < 2; ++k) {
      diff = std::max(diff, std::abs(s1.data()[i][k] - s2.data()[i][k]));
      norm = std::max(norm, std::abs(s2.data()[i][k]));
    }
  EXPECT_LT(diff, 1e-13 * norm) << "forward";
  measured.backward(s1.data());
  estimated.backward(s2.data());
  // Real grids now: compare the grid points, not the rows' padding.
  const double* r1 = SpmeGrid::real_part(s1.data());
  const double* r2 = SpmeGrid::real_part(s2.data());
  const int K3 = measured.size(2), R = measured.row_stride();
  double bdiff = 0, bnorm = 0;
  for (std::size_t row = 0; row < static_cast<std::size_t>(measured.size(0)) * measured.size(1); ++row)
    for (int l = 0; l < K3; ++l)
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = (row * R + l) * 3 + c;
        bdiff = std::max(bdiff, std::abs(r1[i] - r2[i]));
        bnorm = std::max(bnorm, std::abs(r2[i]));
      }
  EXPECT_LT(bdiff, 1e-13 * bnorm) << "backward";
}
