#include "libsolver/stepper/contact_force.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"
#include "geometry/surface/cell_grids.h"
#include "libsolver/membrane/membrane_force.h"
#include "libsolver/membrane/membrane_law.h"
#include "libsolver/stepper/cell_stepper.h"
#include "libsolver/stepper/held_shapes.h"

using namespace rbcflow;

namespace {

constexpr double kPi = std::numbers::pi;

SHCoeffs sphere_at(const Eigen::Vector3d& centre, int order) {
  SHSurface s = make_sphere(order);
  s.translate(centre);
  return s.coeffs();
}

// The integral of f over [a, b] by composite Gauss-Legendre (4 points on each of n panels).
double integrate(const std::function<double(double)>& f, double a, double b, int n) {
  static const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const double h = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) sum += 0.5 * h * w[k] * f(a + h * (i + 0.5 + 0.5 * x[k]));
  return sum;
}

// The force on a rigid unit sphere from another at gap g: the integral over it of t(|x - c_b| -
// 1) along the other's normal (x - c_b) / |x - c_b|, about the line of centres, to 1e-12.
double two_sphere_force(const ContactLaw& law, double g) {
  return integrate(
      [&](double theta) {
        const double ax = std::cos(theta) - (2.0 + g), r = std::hypot(ax, std::sin(theta));
        return 2.0 * kPi * law.traction(r - 1.0) * ax / r * std::sin(theta);
      },
      0.0, kPi, 20000);
}

// The net force of `density` (grid points x 3) over the surface `x` on the grid of `t`.
Eigen::Vector3d net_force(const SHCoeffs& x, const SHTransform& t, const Eigen::MatrixXd& density) {
  const SurfaceGeometry g = surface_geometry(x, t);
  return (density.transpose() * g.area_weight);
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

// Two unit spheres (Skalak, E_S = 10, E_D = 30, N = 12, lambda = 1, free space) pressed
// together by body forces +-F, F = 2, with the repulsion (delta = 0.3, kappa = 100) and no
// kinematic removal: from a gap of 0.25 they close to rest where the repulsion carries F,
// never nearer than delta / 20 (where the law saturates). At rest the flow exerts no net force
// on a cell, so the repulsion's net force on each equals F: measured 1.85 at t = 12, the
// membranes still flattening slowly (the gap opening 1e-4 a time unit), so within 10%. Rigid
// spheres would carry F at a gap of 0.195 (the exact integral); flattened ones spread the load
// over more of their area, so their gap is wider at equal force: measured 0.239 (the grid's
// closest points).
TEST(ContactForce, TwoSpheresPressedTogetherComeToRestApart) {
  const int order = 12;
  auto grids = CellGrids::make(order, 2 * order);
  const ContactLaw law{0.3, 100.0};
  const double force = 2.0;
  std::vector<Cell> cells;
  for (int k = 0; k < 2; ++k) {
    Cell c;
    c.shape = make_sphere(order);
    c.shape.translate(Eigen::Vector3d(k * 2.25, 0, 0));
    c.membrane = std::make_shared<const Membrane>(c.shape, grids,
                                                  MembraneParameters{make_membrane_law("skalak", 10.0, 30.0), 0.1});
    c.body_force = Eigen::Vector3d((k == 0 ? 1 : -1) * force, 0, 0);
    cells.push_back(std::move(c));
  }
  CellStepperOptions o;
  o.dt = 8e-3;
  o.contact = law;
  o.volume_constraint = true;
  CellStepper stepper(cells, grids, o);
  double smallest = 1.0, gap = 0.0, gap_before = 0.0;
  for (int step = 1; step <= 1500; ++step) {
    const StepReport r = stepper.step();
    ASSERT_TRUE(r.contact.has_value());
    gap = r.contact->min_separation;
    smallest = std::min(smallest, gap);
    if (step == 1000) gap_before = gap;
    if (step % 100 == 0) std::printf("t = %.2f  gap %.5f  max traction %.3f\n", stepper.time(), gap, r.contact->max_traction);
  }
  ContactReport report;
  std::vector<SHCoeffs> shapes{stepper.cells()[0].shape.coeffs(), stepper.cells()[1].shape.coeffs()};
  const Eigen::MatrixXd density =
      contact_force_density(shapes, {0, 1}, *grids->n_grid, Eigen::Vector3d::Zero(), nullptr, law, report);
  const int np = grids->n_grid->grid().size();
  const Eigen::Vector3d f0 = net_force(shapes[0], *grids->n_grid, density.topRows(np));
  const Eigen::Vector3d f1 = net_force(shapes[1], *grids->n_grid, density.bottomRows(np));
  // The rigid spheres' gap for F, by bisection on the exact integral (decreasing in g).
  double lo = 0.02, hi = 0.3;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (-two_sphere_force(law, mid) > force ? lo : hi) = mid;
  }
  std::printf("final gap %.5f (rigid spheres %.5f), smallest %.5f, repulsion on the cells %.5f, %.5f\n", gap, lo,
              smallest, f0.x(), f1.x());
  EXPECT_GT(smallest, law.range / 20);
  EXPECT_NEAR(-f0.x(), force, 0.1 * force);
  EXPECT_NEAR(f1.x(), force, 0.1 * force);
  EXPECT_LT(std::abs(gap - gap_before), 0.01 * gap);  // at rest: the last 500 steps moved it < 1%
  EXPECT_GT(gap, lo);
  EXPECT_LT(gap, law.range);
}
