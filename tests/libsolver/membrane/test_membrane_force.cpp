#include "libsolver/membrane/membrane_force.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

namespace {

constexpr double pi = std::numbers::pi;

MembraneParameters params(const std::string& law, double eb = 0.0669) {
  const double es = law == "hookean" ? 1.0 : 12.4, ed = law == "hookean" ? 2.5 : 200.0;
  return {std::shared_ptr<const MembraneLaw>(make_membrane_law(law, es, ed)), eb};
}

// A smooth (not band-limited) deformation of the biconcave cell, order N.
SHSurface deformed_biconcave(int N, double amplitude = 0.08) {
  const double r0 = evans_fung_radius();
  return surface_from_map(N, [r0, amplitude](const Eigen::Vector3d& u) {
    const double s2 = 1.0 - u.z() * u.z();
    const Eigen::Vector3d x(r0 * u.x(), r0 * u.y(), 0.5 * r0 * u.z() * (0.207161 + 2.002558 * s2 - 1.122762 * s2 * s2));
    const Eigen::Vector3d d(u.x() * u.y() + 0.3 * u.z(), std::sin(1.3 * u.z() + 0.2 * u.x()), u.x() * u.x() - 0.5 * u.y());
    return Eigen::Vector3d(x + amplitude * d);
  });
}

Eigen::Matrix3d rotation() { return Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix(); }

}  // namespace

TEST(MembraneForce, VanishesOnTheReferenceShapeForEveryLaw) {
  const int N = 16;
  auto grids = CellGrids::make(N, 2 * N);
  for (const SHSurface& ref : {make_sphere(N), make_ellipsoid(N, Eigen::Vector3d(0.8, 0.9, 1.0)), make_biconcave(N)}) {
    for (const std::string law : {"skalak", "neo-hookean", "hookean"}) {
      const Membrane m(ref, grids, params(law));
      const MembraneState s = m.compute(ref.coeffs());
      EXPECT_LT(s.traction_grid.cwiseAbs().maxCoeff(), 1e-10) << law;
      EXPECT_LT((s.dilatation.array() - 1.0).abs().maxCoeff(), 1e-12) << law;
    }
  }
}

TEST(MembraneForce, RigidMotionsOfDeformedAndReferenceTogetherChangeNothing) {
  const int N = 16;
  auto grids = CellGrids::make(N, 2 * N);
  const SHSurface ref = make_biconcave(N), cur = deformed_biconcave(N);
  const MembraneState s0 = Membrane(ref, grids, params("skalak")).compute(cur.coeffs());
  const Eigen::Vector3d shift(3.0, -1.0, 0.5);

  SHSurface ref1 = ref, cur1 = cur;  // both moved: the traction rotates with them
  ref1.rotate(rotation());
  ref1.translate(shift);
  cur1.rotate(rotation());
  cur1.translate(shift);
  const MembraneState s1 = Membrane(ref1, grids, params("skalak")).compute(cur1.coeffs());
  const double scale = s0.traction_grid.cwiseAbs().maxCoeff();
  EXPECT_LT((s1.traction_grid - s0.traction_grid * rotation().transpose()).cwiseAbs().maxCoeff(), 1e-11 * scale);
  EXPECT_NEAR(s1.elastic_energy, s0.elastic_energy, 1e-12 * s0.elastic_energy);

  SHSurface cur2 = cur;  // only the deformed shape moved rigidly: the same stresses, rotated
  cur2.rotate(rotation());
  cur2.translate(shift);
  const MembraneState s2 = Membrane(ref, grids, params("skalak")).compute(cur2.coeffs());
  EXPECT_LT((s2.traction_grid - s0.traction_grid * rotation().transpose()).cwiseAbs().maxCoeff(), 1e-11 * scale);
  EXPECT_LT((s2.principal_tension - s0.principal_tension).cwiseAbs().maxCoeff(), 1e-11 * scale);
}

// The rest metrics are intrinsic: those of a reference shape serve every rotated and
// translated copy of it (the cells of a run share one set), to rounding; a mirror image
// (det -1) turns the normal and with it the curvature, and does not share them.
TEST(MembraneForce, RigidlyMovedReferencesShareTheirRestMetrics) {
  const int N = 16;
  auto grids = CellGrids::make(N, 2 * N);
  const SHSurface ref = make_biconcave(N);
  const auto shared = std::make_shared<const RestMetrics>(ref, *grids);
  SHSurface moved = ref, cur = deformed_biconcave(N), mirrored = ref;
  moved.rotate(rotation());
  moved.translate(Eigen::Vector3d(3.0, -1.0, 0.5));
  cur.rotate(rotation());
  cur.translate(Eigen::Vector3d(3.0, -1.0, 0.5));
  mirrored.transform(Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal() * rotation());
  const RestMetrics own(moved, *grids), mirror(mirrored, *grids);
  // Relative to the largest of each kind (the axisymmetric shape's a^{12} and b^1_2 are 0).
  const double metric = shared->inv11.cwiseAbs().maxCoeff(), curvature = shared->b11.cwiseAbs().maxCoeff();
  const auto difference = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).cwiseAbs().maxCoeff(); };
  for (auto field : {&RestMetrics::inv11, &RestMetrics::inv12, &RestMetrics::inv22})
    EXPECT_LT(difference(own.*field, *shared.*field), 1e-12 * metric);
  EXPECT_LT(difference(own.det, shared->det), 1e-12 * shared->det.cwiseAbs().maxCoeff());
  for (auto field : {&RestMetrics::b11, &RestMetrics::b12, &RestMetrics::b21, &RestMetrics::b22})
    EXPECT_LT(difference(own.*field, *shared.*field), 1e-12 * curvature);
  EXPECT_GT(difference(mirror.b11, shared->b11), curvature);  // -b: a difference of 2 |b|

  const MembraneState by_own = Membrane(moved, grids, params("skalak")).compute(cur.coeffs());
  const Membrane sharing(moved, grids, params("skalak"), shared);
  EXPECT_EQ(sharing.rest_metrics(), shared);
  const MembraneState by_shared = sharing.compute(cur.coeffs());
  const double scale = by_own.traction_grid.cwiseAbs().maxCoeff();
  EXPECT_LT((by_shared.traction_grid - by_own.traction_grid).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_NEAR(by_shared.elastic_energy, by_own.elastic_energy, 1e-12 * by_own.elastic_energy);
  EXPECT_THROW(Membrane(moved, CellGrids::make(N, 3 * N), params("skalak"), shared), std::invalid_argument);
}

namespace {

// A random smooth (band-limited, degrees < 5) deformation of `ref` of size `amplitude`.
SHCoeffs random_deformation(const SHSurface& ref, double amplitude, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> nd;
  SHCoeffs d(5, 3);
  for (Eigen::Index i = 0; i < d.values().size(); ++i) d.values().data()[i] = amplitude * nd(gen);
  SHCoeffs x = ref.coeffs();
  x.values() += d.resampled(ref.order()).values();
  return x;
}

// |integral f dA| / integral |f| dA and |integral x cross f dA| / integral |x||f| dA, on the
// M grid (exact quadrature for the band-limited f against the smooth area element).
std::pair<double, double> equilibrium_error(const SHCoeffs& x, const MembraneState& s, const CellGrids& grids) {
  const SurfaceGeometry g = surface_geometry(x, *grids.m_grid);
  const Eigen::MatrixXd f = grids.m_grid->synthesize(s.traction);
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  double fn = 0.0, tn = 0.0;
  for (int p = 0; p < g.size(); ++p) {
    const Eigen::Vector3d fp = f.row(p), xp = g.x.row(p);
    force += g.area_weight[p] * fp;
    torque += g.area_weight[p] * xp.cross(fp);
    fn += g.area_weight[p] * fp.norm();
    tn += g.area_weight[p] * fp.norm() * xp.norm();
  }
  return {force.norm() / fn, torque.norm() / tn};
}

double work_on_m_grid(const SHCoeffs& x, const MembraneState& s, const SHCoeffs& dx, const CellGrids& grids) {
  const SurfaceGeometry g = surface_geometry(x, *grids.m_grid);
  const Eigen::MatrixXd f = grids.m_grid->synthesize(s.traction), d = grids.m_grid->synthesize(dx);
  return ((f.array() * d.array()).rowwise().sum() * g.area_weight.array()).sum();
}

}  // namespace

TEST(MembraneForce, IsSelfEquilibratedOnDeformedSpheres) {
  // integral f dA = 0 and integral x cross f dA = 0 for random smooth deformations of a
  // sphere with ~1% strains (Skalak with bending, parameters (35)); spectrally small.
  std::printf("   N    M   force       torque\n");
  double prev = 1.0;
  for (int N : {8, 12, 16}) {
    auto grids = CellGrids::make(N, 3 * N);
    const SHSurface ref = make_sphere(N);
    const SHCoeffs x = random_deformation(ref, 0.003, 3);
    const auto [ef, et] = equilibrium_error(x, Membrane(ref, grids, params("skalak")).compute(x), *grids);
    std::printf("  %2d  %3d   %.2e    %.2e\n", N, 3 * N, ef, et);
    EXPECT_LT(std::max(ef, et), prev);
    prev = std::max(ef, et);
  }
  EXPECT_LT(prev, 1e-8);  // the acceptance figure at N = 16, M = 48
}

TEST(MembraneForce, IsSelfEquilibratedOnDeformedRedCells) {
  // On the biconcave reference the traction's spectrum decays more slowly (the rim): the
  // truncation to n < N limits the balance at N = 16 (~2e-5); it converges spectrally.
  // Torque balance needs the antisymmetric tension of (22b) (nonzero for this reference).
  std::printf("   N    M   force       torque\n");
  double prev = 1.0;
  for (int N : {12, 16, 24, 32}) {
    auto grids = CellGrids::make(N, 3 * N);
    const SHSurface ref = make_biconcave(N);
    const SHCoeffs x = random_deformation(ref, 0.003, 3);
    const auto [ef, et] = equilibrium_error(x, Membrane(ref, grids, params("skalak")).compute(x), *grids);
    std::printf("  %2d  %3d   %.2e    %.2e\n", N, 3 * N, ef, et);
    EXPECT_LT(std::max(ef, et), prev);
    prev = std::max(ef, et);
  }
  EXPECT_LT(prev, 1e-8);  // N = 32
}

TEST(MembraneForce, IsotropicInflationFollowsLaplaceLaw) {
  // Sphere r0 = 1 inflated to r: isotropic tension tau, from each law in closed form;
  // f = (2 tau / r) n, outward (the membrane pulls inward on the fluid).
  const int N = 12;
  auto grids = CellGrids::make(N, 2 * N);
  for (double r : {1.05, 0.97}) {
    const double l2 = r * r;
    struct Case { std::string law; double tau; };
    const Case cases[] = {{"skalak", 12.4 * (l2 - 1) / 2 + 200 * l2 * (l2 * l2 - 1) / 2},
                          {"neo-hookean", 12.4 * (1 - std::pow(r, -6))},
                          {"hookean", (2.5 + 1.0) * (l2 - 1)}};
    for (const Case& c : cases) {
      const Membrane m(make_sphere(N), grids, params(c.law, 0.0));
      const SHSurface cur = make_sphere(N, r);
      const MembraneState s = m.compute(cur.coeffs());
      const SurfaceGeometry g = cur.geometry(*grids->n_grid);
      const Eigen::MatrixXd expected = g.normal * (2 * c.tau / r);
      EXPECT_LT((s.traction_grid - expected).cwiseAbs().maxCoeff(), 1e-10 * std::abs(2 * c.tau / r)) << c.law << " r " << r;
      EXPECT_LT((s.principal_tension.array() - c.tau).abs().maxCoeff(), 1e-10 * std::abs(c.tau)) << c.law;
      EXPECT_LT((s.dilatation.array() - l2).abs().maxCoeff(), 1e-12);
    }
  }
}

TEST(MembraneForce, VirtualWorkOfInPlaneLaws) {
  // dE/de (central differences of E = integral W dA_ref) = integral f . dX dA for random
  // smooth perturbations dX of a deformed red cell, N = 24, M = 72.
  const int N = 24;
  auto grids = CellGrids::make(N, 3 * N);
  const SHSurface ref = make_biconcave(N);
  const SHCoeffs x = random_deformation(ref, 0.01, 11);
  for (const std::string law : {"skalak", "neo-hookean", "hookean"}) {
    const Membrane m(ref, grids, params(law, 0.0));
    const SHCoeffs dx = random_deformation(make_sphere(N, 0.0), 0.1, 17);
    const double h = 1e-4;
    SHCoeffs plus = x, minus = x;
    plus.values() += h * dx.values();
    minus.values() -= h * dx.values();
    const double dE = (m.elastic_energy(plus) - m.elastic_energy(minus)) / (2 * h);
    const double work = work_on_m_grid(x, m.compute(x), dx, *grids);
    const double rel = std::abs(dE - work) / std::abs(dE);
    std::printf("  %-12s dE/de = %.10e   int f.dX dA = %.10e   rel %.1e\n", law.c_str(), dE, work, rel);
    EXPECT_LT(rel, 1e-6) << law;
  }
}

TEST(MembraneForce, VirtualWorkOfBendingForSmallDeformationsOfASphere) {
  // The bending law (21) is not variational in general, but for normal deformations zeta of
  // a sphere its traction is, at leading order, the variation of the Helfrich energy
  // (E_B / 2) integral (2H)^2 dA (spontaneous curvature 0), whose sphere modes have the
  // stiffness E_B L (L - 2) (test_membrane_modes). The mismatch must fall like the amplitude.
  const int N = 16;
  auto grids = CellGrids::make(N, 2 * N);
  const double eb = 1.0;
  const Membrane m(make_sphere(N), grids, {std::make_shared<SkalakLaw>(1e-12, 0.0), eb});
  const SHTransform fine(2 * N, SphGrid::gauss(2 * N), 2);
  auto helfrich = [&](const SHCoeffs& x) {
    const SurfaceGeometry g = surface_geometry(x, fine);
    return 0.5 * eb * ((2 * g.mean_curvature.array()).square() * g.area_weight.array()).sum();
  };
  // Radial fields zeta(u) u: zeta a random scalar of degrees 2..5 (degrees 0 and 1, a
  // dilation and a translation, leave the Helfrich energy unchanged).
  auto radial = [&](double amplitude, unsigned seed) {
    std::mt19937 gen(seed);
    std::normal_distribution<double> nd;
    SHCoeffs z(6, 1);
    for (int mm = 0; mm < 6; ++mm) {
      for (int l = std::max(mm, 2); l < 6; ++l) {
        z.a(l, mm) = nd(gen);
        if (mm > 0) z.b(l, mm) = nd(gen);
      }
    }
    const Eigen::MatrixXd zeta = fine.synthesize(z);
    const Eigen::MatrixXd u = fine.synthesize(make_sphere(N).coeffs());
    return fine.analyze(u.array().colwise() * (amplitude * zeta.col(0).array()), N);
  };
  const SHCoeffs dx = radial(1.0, 21);
  double prev = 0.0;
  for (double amp : {1e-2, 1e-3, 1e-4}) {
    SHCoeffs x = make_sphere(N).coeffs();
    x.values() += radial(amp, 20).values();
    const double h = 1e-3 * amp;
    SHCoeffs plus = x, minus = x;
    plus.values() += h * dx.values();
    minus.values() -= h * dx.values();
    const double dE = (helfrich(plus) - helfrich(minus)) / (2 * h);
    const double work = work_on_m_grid(x, m.compute(x), dx, *grids);
    const double rel = std::abs(dE - work) / std::abs(dE);
    std::printf("  amplitude %.0e: dE_H/de = %.8e  int f.dX dA = %.8e  rel %.2e\n", amp, dE, work, rel);
    if (prev > 0) {
      EXPECT_LT(rel, prev / 5) << "mismatch not O(amplitude)";
    }
    prev = rel;
  }
  EXPECT_LT(prev, 1e-3);
}

TEST(MembraneForce, ConvergesSpectrallyWithOrder) {
  // The traction of one fixed deformed red cell (the Evans-Fung shape plus a band-limited
  // deformation, so the same surface at every N), sampled at fixed points, against N = 48.
  const Eigen::Matrix<double, 4, 2> points{{0.4, 0.3}, {1.2, 2.0}, {2.0, 4.0}, {2.9, 5.5}};
  auto traction_at_points = [&](int N) {
    auto grids = CellGrids::make(N, 2 * N);
    const SHSurface ref = make_biconcave(N);
    const MembraneState s = Membrane(ref, grids, params("skalak")).compute(random_deformation(ref, 0.003, 3));
    Eigen::MatrixXd f(4, 3);
    for (int k = 0; k < 4; ++k) f.row(k) = sh_evaluate(s.traction, points(k, 0), points(k, 1));
    return f;
  };
  const Eigen::MatrixXd ref = traction_at_points(48);
  std::printf("   N   max |f - f_48| / max |f_48|   (M = 2N)\n");
  double prev = 1e300;
  for (int N : {8, 12, 16, 24, 32}) {
    const double err = (traction_at_points(N) - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
    std::printf("  %2d   %.3e\n", N, err);
    EXPECT_LT(err, prev);
    prev = err;
  }
  // Geometric (spectral) decay, about 10x per 8 more modes for the red cell's sharp rim:
  // 4.5e-4 measured at N = 32.
  EXPECT_LT(prev, 1e-3);
}

TEST(MembraneForce, RejectsBadInput) {
  auto grids = CellGrids::make(8, 16);
  EXPECT_THROW(Membrane(make_sphere(8), grids, MembraneParameters{}), std::invalid_argument);
  EXPECT_THROW(Membrane(make_sphere(12), grids, params("skalak")), std::invalid_argument);
  const Membrane m(make_sphere(8), grids, params("skalak"));
  EXPECT_THROW(m.compute(SHCoeffs(9, 3)), std::invalid_argument);
}
