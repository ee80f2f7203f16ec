#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "libsolver/spme/bspline.h"

using namespace rbcflow;

TEST(BSpline, KnownValuesAndSymmetry) {
  // M_4 at the integers: 1/6, 2/3, 1/6; M_2 the hat on [0, 2].
  EXPECT_NEAR(bspline(4, 1.0), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(bspline(4, 2.0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(bspline(4, 3.0), 1.0 / 6.0, 1e-15);
  EXPECT_EQ(bspline(4, 0.0), 0.0);
  EXPECT_EQ(bspline(4, 4.5), 0.0);
  for (int p = kMinSplineOrder; p <= kMaxSplineOrder; ++p)
    for (double u : {0.3, 1.7, 2.25, 3.9})
      EXPECT_NEAR(bspline(p, u), bspline(p, p - u), 1e-14) << p << " " << u;
}

// The recursion M_p(u) = [u M_{p-1}(u) + (p - u) M_{p-1}(u - 1)] / (p - 1) and the derivative
// identity M_p'(u) = M_{p-1}(u) - M_{p-1}(u - 1).
TEST(BSpline, RecursionAndDerivative) {
  for (int p = 5; p <= kMaxSplineOrder; ++p)
    for (double u : {0.4, 1.3, 2.8, 4.1}) {
      const double rec = (u * bspline(p - 1, u) + (p - u) * bspline(p - 1, u - 1)) / (p - 1);
      EXPECT_NEAR(bspline(p, u), rec, 1e-15);
      const double h = 1e-6;
      const double derivative = (bspline(p, u + h) - bspline(p, u - h)) / (2 * h);
      EXPECT_NEAR(derivative, bspline(p - 1, u) - bspline(p - 1, u - 1), 1e-9);
    }
}

TEST(BSpline, WeightsArePartitionOfUnityWithExactFirstMoment) {
  for (int p = kMinSplineOrder; p <= kMaxSplineOrder; ++p)
    for (double t : {0.0, 0.25, 0.5, 0.999}) {
      double w[kMaxSplineOrder];
      bspline_weights(p, t, w);
      EXPECT_NEAR(std::accumulate(w, w + p, 0.0), 1.0, 1e-14);
      // sum_j w_j (t + j) = p / 2: the spline is centred.
      double moment = 0;
      for (int j = 0; j < p; ++j) {
        EXPECT_NEAR(w[j], bspline(p, t + j), 1e-15);
        moment += w[j] * (t + j);
      }
      EXPECT_NEAR(moment, p / 2.0, 1e-13);
    }
}

TEST(BSpline, ModulusOfTheEulerSplines) {
  for (int p = kMinSplineOrder; p <= kMaxSplineOrder; ++p) {
    const int K = 16;
    const std::vector<double> m = bspline_modulus(p, K);
    EXPECT_NEAR(m[0], 1.0, 1e-14);  // sum_j M_p(j + 1) = 1
    for (int k = 1; k < K; ++k) EXPECT_NEAR(m[k], m[K - k], 1e-14);
    if (p % 2 == 1) {
      EXPECT_NEAR(m[K / 2], 0.0, 1e-14);  // odd orders vanish at Nyquist
    } else {
      EXPECT_GT(m[K / 2], 1e-4);
    }
  }
}

TEST(BSpline, RejectsUnsupportedOrders) {
  EXPECT_THROW(check_spline_order(3), std::invalid_argument);
  EXPECT_THROW(check_spline_order(11), std::invalid_argument);
  EXPECT_NO_THROW(check_spline_order(7));
}
