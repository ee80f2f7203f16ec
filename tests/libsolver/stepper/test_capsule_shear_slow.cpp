// Capsule in simple shear at Ca_G = 0.3 (issue 7 validation 4, the large-deformation point;
// label slow): the spherical neo-Hookean capsule of test_capsule_shear.cpp, lambda = 1, reaches
// a steady Taylor deformation. Published boundary-integral values for this case are near 0.39
// (Ramanujan & Pozrikidis, JFM 361, 1998; Lac et al., JFM 516, 2004, docs/references.md section 5).
// N = 16, M = 32, AB2 (forward Euler inflates a tank-treading membrane by O(dt): the volume
// drift of the fast test), half the limit (37) (AB2's real stability interval is half of
// Euler's), twelve small-deformation relaxation times 1 / (0.248 G_s) = 4 Ca_G / gamma.
#include <gtest/gtest.h>

#include "capsule_shear_support.h"

using namespace rbcflow;
using namespace rbcflow::shear_test;

TEST(CapsuleShearSlow, ReachesSteadyDeformationAtCa03) {
  const ShearRun r = run_shear(0.3, 16, 32, 0.5, 12.0, 1.0, TimeScheme::ab2);
  std::printf("  Ca_G = 0.3: D = %.4f  theta/pi = %.4f  dD over the last t_relax = %.1e  dV = %.1e  (%d steps)\n",
              r.deformation, r.inclination / std::numbers::pi, r.deformation_change, r.volume_error, r.steps);
  EXPECT_LT(r.deformation_change, 2e-3 * r.deformation) << "not steady";
  // The published values are read from graphs (to about +-0.01) and differ between codes by a
  // few percent: 5% around 0.39. Measured 0.3976, theta/pi = 0.1400.
  EXPECT_NEAR(r.deformation / 0.39, 1.0, 0.05);
}
