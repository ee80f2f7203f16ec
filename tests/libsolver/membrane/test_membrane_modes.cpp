// Linear stiffness of a spherical capsule against the closed-form modes of docs/references.md
// section 4: for xi = A Y r + B grad_s Y + C r x grad_s Y on the unit sphere, the traction
// (the negative of the membrane load, f = K xi) projects onto
//   radial:     K_rr A + K_rp B,       K_rr = 4 K_s (+ E_B L (L - 2)),  K_rp = -2 K_s L
//   poloidal:   K_pr A + K_pp B,       K_pr = -2 K_s,  K_pp = K_s L + G_s (L - 2)
//   toroidal:   K_tt C,                K_tt = G_s (L - 2),  L = l (l + 1),
// with (G_s, K_s) the small-strain moduli of each law. The bending term is the classical
// L (L - 2) stiffness of a sphere (Helfrich; Milner & Safran 1987) for the linear law (21).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/membrane/membrane_force.h"

using namespace rbcflow;

namespace {

struct ModeFields {
  Eigen::MatrixXd u, Y, gradY, curlY;  // on a grid: r-hat, Y_lm, grad_s Y, r-hat x grad_s Y
};

ModeFields mode_fields(const SHTransform& t, int l, int m) {
  SHCoeffs y(t.order(), 1);
  y.a(l, m) = 1.0;
  ModeFields f;
  const SphGrid& g = t.grid();
  f.Y = t.synthesize(y);
  const Eigen::MatrixXd yt = t.synthesize(y, 1, 0), yp = t.synthesize(y, 0, 1);
  f.u.resize(g.size(), 3);
  f.gradY.resize(g.size(), 3);
  f.curlY.resize(g.size(), 3);
  for (int p = 0; p < g.size(); ++p) {
    const double th = g.theta()[p / g.n_phi()], ph = g.phi(p % g.n_phi());
    const Eigen::Vector3d u(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    const Eigen::Vector3d e_th(std::cos(th) * std::cos(ph), std::cos(th) * std::sin(ph), -std::sin(th));
    const Eigen::Vector3d e_ph(-std::sin(ph), std::cos(ph), 0.0);
    const Eigen::Vector3d grad = yt(p, 0) * e_th + yp(p, 0) / std::sin(th) * e_ph;
    f.u.row(p) = u;
    f.gradY.row(p) = grad;
    f.curlY.row(p) = u.cross(grad);
  }
  return f;
}

// Central-difference linear response f'(xi) of the membrane at the unit sphere.
Eigen::MatrixXd linear_traction(const Membrane& m, const SHCoeffs& xi, double eps) {
  SHCoeffs plus = make_sphere(m.grids().order).coeffs(), minus = plus;
  plus.values() += eps * xi.values();
  minus.values() -= eps * xi.values();
  return (m.compute(plus).traction_grid - m.compute(minus).traction_grid) / (2 * eps);
}

struct Projection { double radial, poloidal, toroidal; };

Projection project(const Eigen::MatrixXd& f, const ModeFields& mf, const SphGrid& g, double L) {
  double yy = 0, r = 0, p = 0, c = 0;
  for (int q = 0; q < g.size(); ++q) {
    const double w = g.sphere_weight(q);
    yy += w * mf.Y(q, 0) * mf.Y(q, 0);
    r += w * f.row(q).dot(mf.u.row(q)) * mf.Y(q, 0);
    p += w * f.row(q).dot(mf.gradY.row(q));
    c += w * f.row(q).dot(mf.curlY.row(q));
  }
  return {r / yy, p / (L * yy), c / (L * yy)};
}

void check_law(const std::string& name, double es, double ed, double eb) {
  const int N = 12, M = 36;
  auto grids = CellGrids::make(N, M);
  const Membrane membrane(make_sphere(N), grids, {std::shared_ptr<const MembraneLaw>(make_membrane_law(name, es, ed)), eb});
  const double Gs = membrane.parameters().law->small_strain_shear_modulus();
  const double Ks = membrane.parameters().law->small_strain_area_modulus();
  const SHTransform sample(2 * N, SphGrid::gauss(2 * N), 1);
  std::printf("  %s (G_s %.3g, K_s %.3g, E_B %.3g): max relative error per l\n", name.c_str(), Gs, Ks, eb);
  for (int l = 2; l <= 10; ++l) {
    const int m = 2;
    const double L = l * (l + 1.0);
    const ModeFields fine = mode_fields(sample, l, m), coarse = mode_fields(*grids->n_grid, l, m);
    auto displacement = [&](double A, double B, double C) {
      const Eigen::MatrixXd xi = A * (fine.u.array().colwise() * fine.Y.col(0).array()).matrix() + B * fine.gradY + C * fine.curlY;
      return sample.analyze(xi, N);
    };
    const double eps = 1e-6;
    const Projection a = project(linear_traction(membrane, displacement(1, 0, 0), eps), coarse, grids->n_grid->grid(), L);
    const Projection b = project(linear_traction(membrane, displacement(0, 1, 0), eps), coarse, grids->n_grid->grid(), L);
    const Projection c = project(linear_traction(membrane, displacement(0, 0, 1), eps), coarse, grids->n_grid->grid(), L);
    const double Krr = 4 * Ks + eb * L * (L - 2), Krp = -2 * Ks * L, Kpr = -2 * Ks, Kpp = Ks * L + Gs * (L - 2);
    const double Ktt = Gs * (L - 2);
    const double err = std::max({std::abs(a.radial / Krr - 1), std::abs(b.radial / Krp - 1),
                                 std::abs(b.poloidal / Kpp - 1), std::abs(c.toroidal / Ktt - 1),
                                 eb == 0 ? std::abs(a.poloidal / Kpr - 1) : 0.0});
    std::printf("    l = %2d  K_rr %.6e  K_rp %.6e  K_pr %.6e  K_pp %.6e  K_tt %.6e   err %.1e\n", l, a.radial,
                b.radial, a.poloidal, b.poloidal, c.toroidal, err);
    EXPECT_LT(err, 1e-6) << name << " l = " << l;
  }
}

}  // namespace

TEST(MembraneModes, HookeanLawMatchesLinearTheory) { check_law("hookean", 1.0, 2.5, 0.0); }
TEST(MembraneModes, SkalakLawMatchesLinearTheory) { check_law("skalak", 12.4, 200.0, 0.0); }
TEST(MembraneModes, NeoHookeanLawMatchesLinearTheory) { check_law("neo-hookean", 1.0, 0.0, 0.0); }
TEST(MembraneModes, BendingAddsHelfrichStiffness) { check_law("hookean", 1.0, 2.5, 0.05); }
