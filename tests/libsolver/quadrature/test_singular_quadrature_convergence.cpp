// Fig. 3 of the paper in full (slow): the identities (38), (39) on the squeezed ellipsoid with
// rotated poles for N = 8 .. 48; order >= 3 and error <= 1e-5 at N = 32.
#include <gtest/gtest.h>

#include "quadrature_test_support.h"

using namespace rbcflow;

TEST(SingularQuadratureConvergence, Figure3IdentitiesOnTheSqueezedEllipsoid) {
  std::printf("   N    single layer (38)   double layer (39)\n");
  std::vector<double> ns, e_single, e_double;
  for (int N : {8, 12, 16, 24, 32, 48}) {
    const auto e = quadrature_test::section8_identity_errors(
        make_squeezed_ellipsoid(N, squeezed_ellipsoid_default_rotation()), N, quadrature_test::accurate_options());
    std::printf("  %2d    %.3e           %.3e\n", N, e.single, e.double_);
    ns.push_back(N);
    e_single.push_back(e.single);
    e_double.push_back(e.double_);
    if (N == 32) {
      EXPECT_LT(e.single, 1e-5);
      EXPECT_LT(e.double_, 1e-5);
    }
  }
  // Observed order between N = 16 and N = 48 (h ~ 1/N).
  const double order_s = std::log(e_single[2] / e_single[5]) / std::log(48.0 / 16.0);
  const double order_d = std::log(e_double[2] / e_double[5]) / std::log(48.0 / 16.0);
  std::printf("  order 16 -> 48: single %.2f, double %.2f\n", order_s, order_d);
  EXPECT_GE(order_s, 3.0);
  EXPECT_GE(order_d, 3.0);
}

// The same with the periodic Ewald sums (box of side 6, tolerance 1e-10) for N = 8 .. 32.
TEST(SingularQuadratureConvergence, Figure3IdentitiesWithEwaldSums) {
  const PeriodicBox box(Eigen::Vector3d::Constant(6.0));
  std::printf("   N    single layer (38)   double layer (39)   (Ewald, box 6)\n");
  std::vector<double> e_single, e_double;
  for (int N : {8, 12, 16, 24, 32}) {
    SHSurface s = make_squeezed_ellipsoid(N, squeezed_ellipsoid_default_rotation());
    s.translate(Eigen::Vector3d(2.9, 3.1, 3.0));
    const auto e = quadrature_test::section8_identity_errors_periodic(s, N, quadrature_test::accurate_options(), box, 1e-10);
    std::printf("  %2d    %.3e           %.3e\n", N, e.single, e.double_);
    e_single.push_back(e.single);
    e_double.push_back(e.double_);
  }
  EXPECT_LT(e_single.back(), 1e-5);
  EXPECT_LT(e_double.back(), 1e-5);
  const double order_s = std::log(e_single[2] / e_single[4]) / std::log(32.0 / 16.0);
  const double order_d = std::log(e_double[2] / e_double[4]) / std::log(32.0 / 16.0);
  std::printf("  order 16 -> 32: single %.2f, double %.2f\n", order_s, order_d);
  EXPECT_GE(order_s, 3.0);
  EXPECT_GE(order_d, 3.0);
}
