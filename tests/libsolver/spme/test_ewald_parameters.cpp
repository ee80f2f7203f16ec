#include <gtest/gtest.h>

#include <cmath>

#include "libsolver/spme/bspline.h"
#include "libsolver/spme/ewald_parameters.h"

using namespace rbcflow;

namespace {
bool is_even_fft_friendly(int n) {
  if (n % 2 != 0) return false;
  for (int f : {2, 3, 5, 7})
    while (n % f == 0) n /= f;
  return n == 1;
}
}  // namespace

TEST(EwaldParameters, ChoiceMeetsItsOwnEstimates) {
  const PeriodicBox box(Eigen::Vector3d(1.0, 2.0, 0.75));
  for (EwaldKernel kernel : {EwaldKernel::stokeslet, EwaldKernel::stresslet})
    for (double tolerance : {1e-3, 1e-6, 1e-10}) {
      const EwaldChoice c = choose_ewald_parameters(kernel, tolerance, box, 5000);
      const EwaldParameters& p = c.parameters;
      EXPECT_NO_THROW(validate(p, box));
      EXPECT_LE(std::hypot(c.real_space_error, c.grid_error), 0.5 * tolerance * (1 + 1e-9));
      EXPECT_NEAR(c.real_space_error, real_space_error(kernel, box, p.xi, p.cutoff), 1e-20);
      EXPECT_NEAR(c.grid_error, spme_grid_error(kernel, box, p.xi, p.grid, p.order), 1e-20);
      for (int d = 0; d < 3; ++d) {
        EXPECT_TRUE(is_even_fft_friendly(p.grid[d])) << p.grid[d];
        // Nearly equal spacing in every direction.
        const double h = box.length(d) / p.grid[d], h0 = box.length(0) / p.grid[0];
        EXPECT_NEAR(h / h0, 1.0, 0.25);
      }
      EXPECT_NEAR(p.alpha(), std::acos(-1.0) / (p.xi * p.xi), 1e-15);
    }
}

// Tighter tolerances cost more; more points per volume shift work to the grid (larger xi).
TEST(EwaldParameters, CostGrowsWithAccuracyAndXiWithDensity) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  double previous = 0.0;
  for (double tolerance : {1e-3, 1e-5, 1e-7, 1e-9}) {
    const EwaldChoice c = choose_ewald_parameters(EwaldKernel::stokeslet, tolerance, box, 10000);
    EXPECT_GT(c.estimated_seconds, previous);
    previous = c.estimated_seconds;
  }
  const double xi_few =
      choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, 1000).parameters.xi;
  const double xi_many =
      choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, 100000).parameters.xi;
  EXPECT_GT(xi_many, 2.0 * xi_few);
}

// A real-space sum assembled once (cheap pairs) moves the choice to a smaller xi: a larger
// cutoff and a coarser grid, within the same error budget and the caller's pair bound.
TEST(EwaldParameters, CheapRealSpaceMovesWorkFromTheGrid) {
  const PeriodicBox box(Eigen::Vector3d(10.5, 10.5, 8.0));
  const long n = 16800, targets = 1200;
  const EwaldChoice plain = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, n, targets);
  const RealSpaceUse cheap{0.01, 5e7};
  const EwaldChoice c = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, n, targets, cheap);
  EXPECT_LT(c.parameters.xi, plain.parameters.xi);
  EXPECT_GT(c.parameters.cutoff, plain.parameters.cutoff);
  const auto points = [](const EwaldParameters& p) { return double(p.grid[0]) * p.grid[1] * p.grid[2]; };
  EXPECT_LT(points(c.parameters), points(plain.parameters));
  EXPECT_LE(std::hypot(c.real_space_error, c.grid_error), 0.5 * 1e-6 * (1 + 1e-9));
  EXPECT_LE(c.neighbours_per_target * targets, cheap.max_pairs);
  // A tight pair bound keeps the cutoff small.
  const EwaldChoice bounded =
      choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, n, targets, RealSpaceUse{0.01, 1e6});
  EXPECT_LE(bounded.neighbours_per_target * targets, 1e6);
  EXPECT_LT(bounded.parameters.cutoff, c.parameters.cutoff);
}

TEST(EwaldParameters, PrintsEverythingRbcflowCheckShows) {
  const EwaldChoice c = choose_ewald_parameters(EwaldKernel::stresslet, 1e-6,
                                                PeriodicBox(Eigen::Vector3d::Ones()), 1000);
  const std::string s = to_string(c);
  for (const char* word : {"stresslet", "tolerance 1e-06", "xi =", "alpha", "cutoff", "grid",
                           "order", "neighbours", "estimated error"})
    EXPECT_NE(s.find(word), std::string::npos) << word << " in\n" << s;
}

TEST(EwaldParameters, RejectsBadInput) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  EXPECT_THROW(choose_ewald_parameters(EwaldKernel::stokeslet, 1e-2, box, 100),
               std::invalid_argument);
  EXPECT_THROW(choose_ewald_parameters(EwaldKernel::stokeslet, 1e-11, box, 100),
               std::invalid_argument);
  EXPECT_THROW(choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, 0),
               std::invalid_argument);
  EXPECT_THROW(choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, 100, 100, RealSpaceUse{0.0, 1e6}),
               std::invalid_argument);
  EXPECT_THROW(choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, 100, 100, RealSpaceUse{0.5, 1e12}),
               std::invalid_argument);
  EXPECT_THROW(validate(EwaldParameters{5.0, 0.3, {16, 16, 16}, 3}, box), std::invalid_argument);
  EXPECT_THROW(validate(EwaldParameters{5.0, 0.3, {16, 17, 16}, 4}, box), std::invalid_argument);
  EXPECT_THROW(validate(EwaldParameters{0.0, 0.3, {16, 16, 16}, 4}, box), std::invalid_argument);
  EXPECT_THROW(validate(EwaldParameters{5.0, -1.0, {16, 16, 16}, 4}, box), std::invalid_argument);
  EXPECT_THROW(validate(EwaldParameters{5.0, 20.0, {16, 16, 16}, 4}, box), std::invalid_argument);
}
