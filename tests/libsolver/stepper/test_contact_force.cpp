#include "libsolver/stepper/contact_force.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "contact_support.h"
#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"
#include "libsolver/stepper/held_shapes.h"

using namespace rbcflow;
using rbcflow::test::integrate;
using rbcflow::test::net_force;
using rbcflow::test::two_sphere_force;

namespace {

constexpr double kPi = std::numbers::pi;

SHCoeffs sphere_at(const Eigen::Vector3d& centre, int order) {
  SHSurface s = make_sphere(order);
  s.translate(centre);
  return s.coeffs();
}

}  // namespace

// t(d) = kappa (delta - d)^2 / (delta d): zero with zero slope at the range, kappa / 2 at half
// of it, 18 kappa at and below the floor delta / 20; the potential is its integral from d to
// delta (its derivative is -t, by central differences to their O(h^2)).
TEST(ContactForce, LawAndPotential) {
  const ContactLaw law{0.2, 3.0};
  EXPECT_EQ(law.traction(0.2), 0.0);
  EXPECT_EQ(law.traction(0.5), 0.0);
  EXPECT_DOUBLE_EQ(law.traction(0.1), 1.5);
  EXPECT_NEAR(law.traction(0.2 - 1e-6) / 1e-6, 0.0, 1e-4);  // slope at the range: t ~ kappa s^2 / delta^2
  EXPECT_DOUBLE_EQ(law.traction(0.01), 3.0 * 0.19 * 0.19 / (0.2 * 0.01));
  EXPECT_DOUBLE_EQ(law.traction(0.0), law.traction(0.01));
  EXPECT_DOUBLE_EQ(law.traction(-0.05), law.traction(0.01));
  EXPECT_EQ(contact_potential(law, 0.2), 0.0);
  for (double d : {0.003, 0.02, 0.07, 0.15, 0.199}) {
    const double h = 1e-6;
    const double slope = (contact_potential(law, d + h) - contact_potential(law, d - h)) / (2 * h);
    EXPECT_NEAR(slope, -law.traction(d), 1e-6 * law.traction(d) + 1e-8) << "d = " << d;
  }
  EXPECT_FALSE(ContactLaw{}.active());
  EXPECT_EQ(ContactLaw{}.traction(0.01), 0.0);
}

// Two unit spheres at gap g = 0.1 (delta = 0.3, kappa = 1): the force on one from the other is
// the integral over it of t(|x - c_b| - 1) along the other's normal (x - c_b) / |x - c_b|, a
// one-dimensional integral about the line of centres computed here to 1e-12. The grid's sum
// converges to it as the contact patch (radius ~0.45) is resolved: t is C^1 at the range, so
// the error falls algebraically, not spectrally, and levels where the range's circle crosses
// the grid. Measured: relative errors 8.9e-4, 2.4e-4, 3.9e-5, 4.7e-5 at N = 12, 16, 24, 32
// (independent of the projection's iterations: 6 or 20 give the same to 8 digits).
TEST(ContactForce, TwoSpheresMatchTheExactIntegral) {
  const double g = 0.1;
  const ContactLaw law{0.3, 1.0};
  const double exact = two_sphere_force(law, g);
  std::vector<double> errors;
  for (int order : {12, 16, 24, 32}) {
    const SHTransform t = SHTransform::gauss(order);
    const std::vector<SHCoeffs> cells{sphere_at({0, 0, 0}, order), sphere_at({2.0 + g, 0, 0}, order)};
    ContactReport report;
    const Eigen::MatrixXd density =
        contact_force_density(cells, {0, 1}, t, Eigen::Vector3d::Zero(), nullptr, law, report);
    const int np = t.grid().size();
    const Eigen::Vector3d fa = net_force(cells[0], t, density.topRows(np));
    const Eigen::Vector3d fb = net_force(cells[1], t, density.bottomRows(np));
    errors.push_back(std::abs(fa.x() / exact - 1.0));
    std::printf("N = %2d  F_a = (%.8f, %.1e, %.1e)  exact %.8f  relative error %.2e  F_a + F_b %.1e  cells in range %d\n",
                order, fa.x(), fa.y(), fa.z(), exact, errors.back(), (fa + fb).norm(), report.cells_near_cells);
    EXPECT_LT(exact, 0.0);  // a push away from the other sphere
    EXPECT_LT(std::abs(fa.y()) + std::abs(fa.z()), 1e-10 * std::abs(exact));
    EXPECT_LT((fa + fb).norm(), 1e-10 * std::abs(exact));  // mirror images: equal and opposite
    EXPECT_EQ(report.cells_near_cells, 2);
    EXPECT_EQ(report.cells_near_wall, 0);
    // The grid's closest points: a node at most half a grid spacing pi / N off the line of
    // centres on each sphere, which opens the gap by less than (pi / N)^2.
    EXPECT_GE(report.min_separation, g - 1e-9);
    EXPECT_LE(report.min_separation, g + std::pow(kPi / order, 2));
  }
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
  EXPECT_LT(errors[2], 1e-4);
  EXPECT_LT(errors[3], 1e-4);
}

// A unit sphere at gap 0.1 from the wall of a D = 3.5 tube (axis z), against the integral of
// t(R - rho) along the wall's normal -(x, y) / rho over the sphere, rho the distance from the
// axis: a two-dimensional integral here to ~1e-9. The wall is triangles of size 0.1, within
// their chord sag 0.1^2 / (8 R) = 7e-4 of the cylinder, which changes t by |dlnt/dd| 7e-4 = 20 x
// 7e-4 = 1.4% at most where the gap is smallest; measured 0.7% at N = 32.
TEST(ContactForce, SphereNearATubeWallMatchesTheExactIntegral) {
  const double g = 0.1, radius = 1.75;
  const ContactLaw law{0.3, 1.0};
  const Eigen::Vector3d centre(radius - 1.0 - g, 0.0, 4.0);
  const auto integrand = [&](double theta, double phi) {
    const Eigen::Vector3d x = centre + Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                       std::cos(theta));
    const double rho = std::hypot(x.x(), x.y());
    return law.traction(radius - rho) * (-x.x() / rho) * std::sin(theta);
  };
  const double exact = integrate(
      [&](double theta) { return integrate([&](double phi) { return integrand(theta, phi); }, -kPi, kPi, 400); }, 0.0,
      kPi, 400);
  const VesselMesh mesh = tube(TubeSpec{2.0 * radius, 2, Eigen::Vector3d(4, 4, 8), 0.1});
  const WallDistance wall(mesh);
  const int order = 32;
  const SHTransform t = SHTransform::gauss(order);
  // The mesh's box is [0, 4] x [0, 4] with the axis at its centre.
  const std::vector<SHCoeffs> cells{sphere_at(centre + Eigen::Vector3d(2, 2, 0), order)};
  ContactReport report;
  const Eigen::MatrixXd density =
      contact_force_density(cells, {0}, t, mesh.period, &wall, law, report);
  const Eigen::Vector3d f = net_force(cells[0], t, density);
  std::printf("F = (%.8f, %.1e, %.1e)  exact %.8f  relative error %.2e\n", f.x(), f.y(), f.z(), exact,
              std::abs(f.x() / exact - 1.0));
  EXPECT_LT(exact, 0.0);  // a push into the lumen, away from the wall at x = R
  EXPECT_LT(std::abs(f.x() / exact - 1.0), 0.014 + 5e-4);  // the sag's bound and the quadrature's (above)
  EXPECT_LT(std::abs(f.y()) + std::abs(f.z()), 0.01 * std::abs(exact));
  EXPECT_EQ(report.cells_near_wall, 1);
  EXPECT_EQ(report.cells_near_cells, 0);
}

// Nothing within range: no force, nothing reported; a target whose shape is not held is a
// logic error.
TEST(ContactForce, FarApartIsZeroAndATargetMustBeHeld) {
  const SHTransform t = SHTransform::gauss(8);
  const ContactLaw law{0.3, 1.0};
  std::vector<SHCoeffs> cells{sphere_at({0, 0, 0}, 8), sphere_at({2.31, 0, 0}, 8)};
  ContactReport report;
  const Eigen::MatrixXd density = contact_force_density(cells, {0, 1}, t, Eigen::Vector3d::Zero(), nullptr, law, report);
  EXPECT_EQ(density.norm(), 0.0);
  EXPECT_EQ(report.cells_in_range, 0);
  EXPECT_EQ(report.max_traction, 0.0);
  cells[1] = shape_not_held(8);
  EXPECT_THROW(contact_force_density(cells, {1}, t, Eigen::Vector3d::Zero(), nullptr, law, report), std::logic_error);
}
