#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/libsolver/spme/ewald_direct.h"
#include "libsolver/spme/ewald_error_estimates.h"
#include "libsolver/spme/spme_plan.h"
#include "test_points.h"

using namespace rbcflow;
using test::random_points;
using test::random_unit_vectors;
using test::random_vectors;

namespace {
const Eigen::Vector3d kL(1.0, 1.2, 0.8);
const PeriodicBox kBox(kL);
struct Data {
  PointField xs = random_points(300, kL, 1), xt = random_points(200, kL, 2);
  PointField f = random_vectors(300, 3), q = random_vectors(300, 4),
             n = random_unit_vectors(300, 5);
  double norm_s = std::cbrt(kBox.volume()) / f.norm();
  double norm_d = std::pow(kBox.volume(), 2.0 / 3.0) / q.norm();  // |n| = 1
};
const Data& data() {
  static const Data d;
  return d;
}
}  // namespace

// The real-space estimates of docs/references.md section 2 against the truncation error measured
// with the brute-force real-space sum (random sources): within 1.5x, as quoted.
TEST(EwaldErrorEstimates, RealSpaceEstimatesMatchMeasurement) {
  const Data& d = data();
  const double xi = 8.0;
  const EwaldDirect exact(kBox, xi);
  const PointField ref_s = exact.real_single_layer(d.xs, d.f, d.xt),
                   ref_d = exact.real_double_layer(d.xs, d.q, d.n, d.xt);
  for (double xi_rc : {2.5, 3.0, 3.5}) {
    const EwaldDirect cut(kBox, xi, xi_rc / xi, 1.0);
    const double es =
        test::rms_difference(cut.real_single_layer(d.xs, d.f, d.xt), ref_s) * d.norm_s;
    const double ed =
        test::rms_difference(cut.real_double_layer(d.xs, d.q, d.n, d.xt), ref_d) * d.norm_d;
    const double ps = real_space_error(EwaldKernel::stokeslet, kBox, xi, xi_rc / xi);
    const double pd = real_space_error(EwaldKernel::stresslet, kBox, xi, xi_rc / xi);
    std::printf(
        "xi r_c = %.1f: stokeslet measured %.2e estimated %.2e; stresslet measured %.2e estimated "
        "%.2e\n",
        xi_rc, es, ps, ed, pd);
    EXPECT_NEAR(std::log(es / ps), 0.0, std::log(1.5));
    EXPECT_NEAR(std::log(ed / pd), 0.0, std::log(1.5));
  }
}

// The calibrated SPME grid-error model against the measured error of the smooth part, even
// orders, xi h from 0.1 to 0.4: within 2x.
TEST(EwaldErrorEstimates, GridEstimateMatchesMeasurement) {
  const Data& d = data();
  for (double xi : {5.0, 10.0}) {
    const EwaldDirect exact(kBox, xi);
    const PointField ref_s = exact.fourier_single_layer(d.xs, d.f, d.xt),
                     ref_d = exact.fourier_double_layer(d.xs, d.q, d.n, d.xt);
    for (int p : {4, 6, 8}) {
      for (const std::array<int, 3>& K :
           {std::array<int, 3>{32, 40, 28}, std::array<int, 3>{48, 60, 40}}) {
        SpmePlan plan(std::make_shared<const SpmeGrid>(kBox, EwaldParameters{xi, 0.1, K, p}), d.xs,
                      d.xt);
        const double es = test::rms_difference(plan.single_layer(d.f), ref_s) * d.norm_s;
        const double ed = test::rms_difference(plan.double_layer(d.q, d.n), ref_d) * d.norm_d;
        const double ps = spme_grid_error(EwaldKernel::stokeslet, kBox, xi, K, p);
        const double pd = spme_grid_error(EwaldKernel::stresslet, kBox, xi, K, p);
        std::printf(
            "xi %.0f p %d K %d: stokeslet measured %.2e estimated %.2e; stresslet measured %.2e "
            "estimated %.2e\n",
            xi, p, K[0], es, ps, ed, pd);
        EXPECT_NEAR(std::log(es / ps), 0.0, std::log(2.0));
        EXPECT_NEAR(std::log(ed / pd), 0.0, std::log(2.0));
      }
    }
  }
}
