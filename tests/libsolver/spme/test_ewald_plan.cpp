#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/kernels/stokes_kernels.h"
#include "libsolver/spme/double_layer_linear.h"
#include "tests/libsolver/spme/ewald_direct.h"
#include "libsolver/spme/ewald_plan.h"
#include "test_points.h"

using namespace rbcflow;
using test::random_points;
using test::random_unit_vectors;
using test::random_vectors;

namespace {
constexpr double pi = std::numbers::pi;

EwaldPlan make_plan(EwaldKernel kernel, double tolerance, const PeriodicBox& box,
                    const PointField& sources, const PointField& targets) {
  const EwaldChoice choice =
      choose_ewald_parameters(kernel, tolerance, box, sources.rows(), targets.rows());
  return EwaldPlan(std::make_shared<const SpmeGrid>(box, choice.parameters), sources, targets);
}

// The normalised RMS error of ewald_error_estimates.h.
double normalised_error(EwaldKernel kernel, const PeriodicBox& box, const PointField& u,
                        const PointField& exact, const PointField& a, const PointField& b) {
  const double ell = std::cbrt(box.volume());
  if (kernel == EwaldKernel::stokeslet) return test::rms_difference(u, exact) * ell / a.norm();
  const double qt = (a.rowwise().squaredNorm().array() * b.rowwise().squaredNorm().array()).sum();
  return test::rms_difference(u, exact) * ell * ell / std::sqrt(qt);
}

struct Random1000 {
  Eigen::Vector3d L{1.0, 1.0, 1.0};
  PeriodicBox box{L};
  PointField xs = random_points(1000, L, 1), xt = random_points(1000, L, 2);
  PointField f = random_vectors(1000, 3), q = random_vectors(1000, 4),
             n = random_unit_vectors(1000, 5);
  PointField exact_single, exact_double;
  Random1000() {
    const EwaldDirect direct(box, 10.0);
    exact_single = direct.single_layer(xs, f, xt);
    exact_double = direct.double_layer(xs, q, n, xt);
  }
};
const Random1000& random1000() {
  static const Random1000 r;
  return r;
}
}  // namespace

// The chooser is neither wrong nor wasteful: for 1,000 random sources (and 1,000 other random
// targets) the measured normalised RMS error against the direct Ewald sum lies between
// tolerance / 30 and the tolerance.
TEST(EwaldPlan, MeetsTheRequestedToleranceWithoutWaste) {
  const Random1000& r = random1000();
  for (double tolerance : {1e-4, 1e-6, 1e-8}) {
    for (EwaldKernel kernel : {EwaldKernel::stokeslet, EwaldKernel::stresslet}) {
      EwaldPlan plan = make_plan(kernel, tolerance, r.box, r.xs, r.xt);
      const bool single = kernel == EwaldKernel::stokeslet;
      const PointField u = single ? plan.single_layer(r.f) : plan.double_layer(r.q, r.n);
      const double error = single ? normalised_error(kernel, r.box, u, r.exact_single, r.f, r.f)
                                  : normalised_error(kernel, r.box, u, r.exact_double, r.q, r.n);
      std::printf("%s, requested %.0e: measured RMS error %.2e (%.2f x requested)\n",
                  to_string(kernel), tolerance, error, error / tolerance);
      EXPECT_LT(error, tolerance);
      EXPECT_GT(error, tolerance / 30);
    }
  }
}

// Targets on sources: the real-space r = 0 term is left out, so u + lim(S^R - G) f = u +
// ewald_real_stokeslet_self(xi) f is the (xi-independent) regular part.
TEST(EwaldPlan, CoincidentTargetsCarryTheSmoothSelfTerm) {
  const Random1000& r = random1000();
  const PointField xs = r.xs.topRows(300), f = r.f.topRows(300);
  EwaldPlan plan = make_plan(EwaldKernel::stokeslet, 1e-8, r.box, xs, xs);
  const EwaldDirect direct(r.box, 12.0);
  const PointField u = plan.single_layer(f) + ewald_real_stokeslet_self(plan.xi()) * f;
  const PointField exact =
      direct.single_layer(xs, f, xs) + ewald_real_stokeslet_self(direct.xi()) * f;
  EXPECT_LT(normalised_error(EwaldKernel::stokeslet, r.box, u, exact, f, f), 1e-8);
}

// Shifting every source and target by a lattice vector leaves the sums unchanged (to
// rounding); by an arbitrary vector, within the tolerance (the grid is not shift-invariant).
TEST(EwaldPlan, PeriodicityAndTranslation) {
  const Eigen::Vector3d L(1.0, 1.3, 0.9);
  const PeriodicBox box(L);
  const PointField xs = random_points(500, L, 11), xt = random_points(200, L, 12);
  const PointField f = random_vectors(500, 13), q = random_vectors(500, 14),
                   n = random_unit_vectors(500, 15);
  const double tolerance = 1e-6;
  for (EwaldKernel kernel : {EwaldKernel::stokeslet, EwaldKernel::stresslet}) {
    const auto product = [&](const Eigen::RowVector3d& shift) {
      const PointField s = xs.rowwise() + shift, t = xt.rowwise() + shift;
      EwaldPlan plan = make_plan(kernel, tolerance, box, s, t);
      return kernel == EwaldKernel::stokeslet ? plan.single_layer(f) : plan.double_layer(q, n);
    };
    const PointField u = product(Eigen::RowVector3d::Zero());
    const PointField lattice = product(Eigen::RowVector3d(2 * L[0], -L[1], 3 * L[2]));
    const PointField moved = product(Eigen::RowVector3d(0.123, -0.456, 0.0789));
    const double e_lattice =
        normalised_error(kernel, box, lattice, u, kernel == EwaldKernel::stokeslet ? f : q, n);
    const double e_moved =
        normalised_error(kernel, box, moved, u, kernel == EwaldKernel::stokeslet ? f : q, n);
    std::printf("%s: lattice shift %.1e, arbitrary shift %.1e (tolerance %.0e)\n",
                to_string(kernel), e_lattice, e_moved, tolerance);
    EXPECT_LT(e_lattice, 1e-10);  // rounding of the shifted positions, amplified by close pairs
    EXPECT_LT(e_moved, tolerance);
  }
}

// Hasimoto's constant through the full SPME machinery (tolerance 1e-10): a point force and
// its own target, S^per - S at the origin = -(4/3)(2.8372975/L) I.
TEST(EwaldPlan, HasimotoConstant) {
  for (double side : {1.0, 3.0}) {
    const PeriodicBox box(Eigen::Vector3d::Constant(side));
    PointField x(1, 3);
    x << 0.2 * side, 0.9 * side, 0.45 * side;
    EwaldPlan plan = make_plan(EwaldKernel::stokeslet, 1e-10, box, x, x);
    Eigen::Matrix3d regular;
    for (int j = 0; j < 3; ++j) {
      const PointField f = Eigen::RowVector3d::Unit(j);
      regular.col(j) =
          (plan.single_layer(f) + ewald_real_stokeslet_self(plan.xi()) * f).row(0).transpose();
    }
    const double expected = -(4.0 / 3.0) * 2.8372975 / side;
    const double error = (regular - expected * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() /
                         std::abs(expected);
    std::printf("L = %.0f: SPME regular part %.10f I, relative error to Hasimoto %.1e\n", side,
                regular(0, 0), error);
    EXPECT_LT(error, 1e-8);  // the constant's 8 digits
  }
}

// docs/references.md section 1 on a sphere R = 0.3 in a unit box (Gauss grid N = 40), targets away
// from the surface: integral G^per n dS = 0, integral T^per_ijk n_k dS = -8 pi (chi - V_S/V)
// delta_ij (-22.29029516 inside, +2.84244607 outside), and with the linear part of eq. (3)
// -8 pi chi delta_ij.
TEST(EwaldPlan, PeriodicLayerIdentitiesOnASphere) {
  const int N = 40;
  const double R = 0.3;
  const PeriodicBox box(Eigen::Vector3d::Ones());
  SHSurface sphere = make_sphere(N, R);
  const Eigen::Vector3d centre(0.45, 0.5, 0.55);
  sphere.translate(centre);
  const SurfaceGeometry g = sphere.geometry(SHTransform::gauss(N));
  PointField targets(5, 3);
  targets << centre.transpose(),                                 // inside
      (centre + Eigen::Vector3d(0.1, -0.05, 0.08)).transpose(),  // inside
      (centre + Eigen::Vector3d(0.0, 0.0, 0.5)).transpose(),     // outside
      (centre + Eigen::Vector3d(0.32, 0.3, -0.2)).transpose(),   // outside
      (centre + Eigen::Vector3d(-0.3, 0.35, 0.05)).transpose();  // outside
  const bool inside[5] = {true, true, false, false, false};
  const PointField weighted_normals = g.normal.array().colwise() * g.area_weight.array();
  const double shift = (4.0 / 3.0) * pi * R * R * R / box.volume();
  EXPECT_NEAR(-8 * pi * (1 - shift), -22.29029516, 1e-8);
  EXPECT_NEAR(-8 * pi * (0 - shift), 2.84244607, 1e-8);

  EwaldPlan single = make_plan(EwaldKernel::stokeslet, 1e-10, box, g.x, targets);
  const double single_error = single.single_layer(weighted_normals).cwiseAbs().maxCoeff();
  EXPECT_LT(single_error, 1e-7);

  EwaldPlan dbl = make_plan(EwaldKernel::stresslet, 1e-10, box, g.x, targets);
  double periodic_error = 0.0, complete_error = 0.0;
  for (int j = 0; j < 3; ++j) {
    const PointField q = g.area_weight * Eigen::RowVector3d::Unit(j);
    const PointField u = dbl.double_layer(q, g.normal);
    const Eigen::RowVector3d linear = double_layer_linear_part(box, g.x, q, g.normal, static_cast<int>(g.x.rows()));
    for (int t = 0; t < 5; ++t) {
      const double chi = inside[t] ? 1.0 : 0.0;
      const Eigen::RowVector3d e = Eigen::RowVector3d::Unit(j);
      periodic_error =
          std::max(periodic_error, (u.row(t) + 8 * pi * (chi - shift) * e).cwiseAbs().maxCoeff());
      complete_error = std::max(
          complete_error, (u.row(t) + linear + 8 * pi * chi * e).cwiseAbs().maxCoeff());
    }
  }
  std::printf(
      "sphere R = 0.3, N = %d: max error single layer %.1e, double layer (periodic part) %.1e, "
      "double layer with the linear part of eq. (3) %.1e\n",
      N, single_error, periodic_error, complete_error);
  EXPECT_LT(periodic_error, 1e-7);
  EXPECT_LT(complete_error, 1e-7);
}

// As the box grows the periodic velocity of a pair of point forces tends to the free-space one,
// u_per - u_free = -(4/3)(2.8372975/L)(f1 + f2) + O(d^2 / L^3) (Hasimoto): measured order 1.
TEST(EwaldPlan, FreeSpaceLimit) {
  PointField xs(2, 3), f(2, 3), xt(1, 3);
  xs << 0.0, 0.0, 0.0, 0.8, 0.3, -0.2;
  f << 1.0, 0.5, -0.2, 0.3, -1.0, 0.4;
  xt << 0.4, -0.6, 0.5;
  Eigen::Vector3d u_free = Eigen::Vector3d::Zero();
  for (int s = 0; s < 2; ++s)
    u_free += stokeslet_apply((xs.row(s) - xt.row(0)).transpose(), f.row(s).transpose());
  const Eigen::Vector3d hasimoto = -(4.0 / 3.0) * 2.8372975 * (f.row(0) + f.row(1)).transpose();
  double previous = 0.0;
  for (double side : {20.0, 40.0, 80.0}) {
    const PeriodicBox box(Eigen::Vector3d::Constant(side));
    const Eigen::RowVector3d centre = Eigen::RowVector3d::Constant(side / 2);
    EwaldPlan plan =
        make_plan(EwaldKernel::stokeslet, 1e-10, box, xs.rowwise() + centre, xt.rowwise() + centre);
    const Eigen::Vector3d correction = plan.single_layer(f).row(0).transpose() - u_free;
    const double leading = (side * correction - hasimoto).norm() / hasimoto.norm();
    std::printf("L = %.0f: |u_per - u_free| = %.4e", side, correction.norm());
    if (previous > 0) {
      const double order = std::log2(previous / correction.norm());
      std::printf(", order %.3f", order);
      EXPECT_NEAR(order, 1.0, 0.02);
    }
    std::printf("; L (u_per - u_free) vs Hasimoto's leading term: relative difference %.1e\n",
                leading);
    EXPECT_LT(leading, 40.0 / (side * side));  // O(d^2 / L^2) relative, d ~ 1
    previous = correction.norm();
  }
}

// One rank's part (ewald_plan.h, SourceRows): on a whole grid, the plans of two blocks of the
// sources sum to the plan of all (the sums are linear in the sources); rows that are not rows
// of the sources are refused.
TEST(EwaldPlan, PlansOfSourceBlocksSumToTheWhole) {
  const Random1000& r = random1000();
  const EwaldChoice choice = choose_ewald_parameters(EwaldKernel::stresslet, 1e-8, r.box, 1000, 1000);
  const auto grid = std::make_shared<const SpmeGrid>(r.box, choice.parameters);
  EwaldPlan whole(grid, r.xs, r.xt), first(grid, r.xs, r.xt, SourceRows{0, 400}),
      rest(grid, r.xs, r.xt, SourceRows{400, 1000});
  const PointField single = first.single_layer(r.f) + rest.single_layer(r.f);
  const PointField double_ = first.double_layer(r.q, r.n) + rest.double_layer(r.q, r.n);
  EXPECT_LT((single - whole.single_layer(r.f)).norm() / single.norm(), 1e-13);
  EXPECT_LT((double_ - whole.double_layer(r.q, r.n)).norm() / double_.norm(), 1e-13);
  EXPECT_THROW(EwaldPlan(grid, r.xs, r.xt, SourceRows{400, 1001}), std::invalid_argument);
  EXPECT_THROW(EwaldPlan(grid, r.xs, r.xt, SourceRows{-1, 10}), std::invalid_argument);
}
