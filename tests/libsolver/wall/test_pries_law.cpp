// The Pries law (Pries, Neuhaus & Gaehtgens, Am. J. Physiol. 263, 1992; docs/references.md
// section 7) as coded: its defining identities (mu_rel = mu_045
// at H_D = 0.45 for every D, mu_rel = 1 without cells), the Fahraeus effect (H_T < H_D in
// narrow tubes, H_T -> H_D in wide ones) and the inversion H_T -> H_D, and the
// non-monotonic trend of fig. 13: a minimum near D = 6.8 um.
#include "libsolver/wall/pries_law.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace rbcflow;

TEST(PriesLaw, DefiningIdentities) {
  for (double D : {4.9, 7.0, 16.9, 100.0}) {
    const double mu45 = 220.0 * std::exp(-1.3 * D) + 3.2 - 2.44 * std::exp(-0.06 * std::pow(D, 0.645));
    EXPECT_NEAR(pries_relative_viscosity(D, 0.45), mu45, 1e-12 * mu45) << D;
    EXPECT_NEAR(pries_relative_viscosity(D, 0.0), 1.0, 1e-12) << D;
  }
}

TEST(PriesLaw, MinimumNearSevenMicrometres) {
  double best_D = 0, best = 1e300;
  for (double D = 3.0; D <= 100.0; D += 0.01) {
    const double mu = pries_relative_viscosity(D, 0.45);
    if (mu < best) {
      best = mu;
      best_D = D;
    }
  }
  std::printf("minimum of mu_rel(D, H_D = 0.45): %.4f at D = %.2f um\n", best, best_D);
  EXPECT_GT(best_D, 6.0);
  EXPECT_LT(best_D, 8.0);
  EXPECT_GT(pries_relative_viscosity(4.9, 0.45), best);
  EXPECT_GT(pries_relative_viscosity(16.9, 0.45), best);
}

TEST(PriesLaw, FahraeusEffectAndInversion) {
  for (double D : {4.9, 5.4, 5.6, 7.0, 9.9, 16.9}) {
    const double hd = discharge_hematocrit(D, 0.30);
    EXPECT_NEAR(hd * fahraeus_ratio(D, hd), 0.30, 1e-12) << D;
    EXPECT_GT(hd, 0.30) << D;  // the tube holds fewer cells than it discharges
  }
  EXPECT_NEAR(fahraeus_ratio(1e4, 0.45), 1.0, 1e-3);  // no Fahraeus effect in wide tubes
}
