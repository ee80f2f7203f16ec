#include "libsolver/membrane/membrane_law.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace rbcflow;

namespace {
// Central differences of W in I1, I2 check the analytic derivatives of each law.
void expect_consistent_derivatives(const MembraneLaw& law) {
  const double h = 1e-5;
  for (double I1 : {-0.3, 0.0, 0.2, 1.1}) {
    for (double I2 : {-0.2, 0.0, 0.4}) {
      const StrainEnergy e = law.energy(I1, I2);
      const double dW1 = (law.energy(I1 + h, I2).W - law.energy(I1 - h, I2).W) / (2 * h);
      const double dW2 = (law.energy(I1, I2 + h).W - law.energy(I1, I2 - h).W) / (2 * h);
      EXPECT_NEAR(e.W1, dW1, 1e-8) << law.name();
      EXPECT_NEAR(e.W2, dW2, 1e-8) << law.name();
    }
  }
}
}  // namespace

TEST(MembraneLaw, DerivativesMatchEnergy) {
  expect_consistent_derivatives(SkalakLaw(12.4, 200));
  expect_consistent_derivatives(NeoHookeanLaw(1.3));
  expect_consistent_derivatives(HookeanLaw(1.0, 2.5));
}

TEST(MembraneLaw, ZeroEnergyInReferenceState) {
  for (const auto& law : {make_membrane_law("skalak", 12.4, 200), make_membrane_law("neo-hookean", 1.0, 0),
                          make_membrane_law("hookean", 1.0, 2.5)}) {
    EXPECT_DOUBLE_EQ(law->energy(0, 0).W, 0.0) << law->name();
  }
}

TEST(MembraneLaw, SmallStrainModuliAsInTheIssue) {
  EXPECT_DOUBLE_EQ(SkalakLaw(12.4, 200).small_strain_shear_modulus(), 6.2);
  EXPECT_DOUBLE_EQ(SkalakLaw(12.4, 200).small_strain_area_modulus(), 206.2);
  EXPECT_DOUBLE_EQ(HookeanLaw(1.0, 2.5).small_strain_shear_modulus(), 1.0);
  EXPECT_DOUBLE_EQ(HookeanLaw(1.0, 2.5).small_strain_area_modulus(), 3.5);
  EXPECT_DOUBLE_EQ(NeoHookeanLaw(2.0).small_strain_area_modulus(), 6.0);
}

TEST(MembraneLaw, UnknownNameAndBadModuliAreErrors) {
  EXPECT_THROW(make_membrane_law("mooney", 1, 1), std::invalid_argument);
  EXPECT_THROW(SkalakLaw(-1, 1), std::invalid_argument);
  EXPECT_THROW(NeoHookeanLaw(0), std::invalid_argument);
}
