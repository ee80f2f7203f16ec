#include "membrane_force.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "geometry/surface/surface_divergence.h"

namespace rbcflow {

// Per-point kinematics and stresses on the M grid.
struct Membrane::Kinematics {
  Eigen::VectorXd inv11, inv12, inv22;  // current a^{ab}
  Eigen::VectorXd J, W;                 // dilatation l1 l2, strain energy per reference area
  Eigen::VectorXd n11, n12, n22;        // contravariant Cauchy tension N^{ab}
  Eigen::MatrixXd dbend;                // b^a_b - b^{aR}_b as columns 11, 12, 21, 22
};

RestMetrics::RestMetrics(const SHSurface& reference, const CellGrids& grids) {
  const SurfaceGeometry g = reference.geometry(*grids.m_grid);
  det = g.a11.array() * g.a22.array() - g.a12.array().square();
  inv11 = g.a22.array() / det.array();
  inv12 = -g.a12.array() / det.array();
  inv22 = g.a11.array() / det.array();
  b11 = inv11.array() * g.b11.array() + inv12.array() * g.b12.array();
  b12 = inv11.array() * g.b12.array() + inv12.array() * g.b22.array();
  b21 = inv12.array() * g.b11.array() + inv22.array() * g.b12.array();
  b22 = inv12.array() * g.b12.array() + inv22.array() * g.b22.array();
}

std::size_t RestMetrics::memory_bytes() const {
  std::size_t n = 0;
  for (const Eigen::VectorXd* v : {&inv11, &inv12, &inv22, &det, &b11, &b12, &b21, &b22}) n += v->size();
  return n * sizeof(double);
}

Membrane::Membrane(const SHSurface& reference, std::shared_ptr<const CellGrids> grids, MembraneParameters params,
                   std::shared_ptr<const RestMetrics> rest)
    : reference_(reference), grids_(std::move(grids)), params_(std::move(params)), rest_(std::move(rest)) {
  if (!grids_) throw std::invalid_argument("Membrane: no grids");
  if (!params_.law) throw std::invalid_argument("Membrane: no constitutive law");
  if (params_.bending_modulus < 0) throw std::invalid_argument("Membrane: bending modulus must be >= 0");
  if (reference_.order() > grids_->order) {
    throw std::invalid_argument("Membrane: reference shape of order " + std::to_string(reference_.order()) +
                                " exceeds the cell order " + std::to_string(grids_->order));
  }
  if (!rest_) rest_ = std::make_shared<const RestMetrics>(reference_, *grids_);
  if (rest_->det.size() != grids_->m_grid->grid().size())
    throw std::invalid_argument("Membrane: rest metrics of another grid");
}

Membrane::Kinematics Membrane::kinematics(const SurfaceGeometry& g) const {
  const int np = g.size();
  Kinematics k;
  const Eigen::ArrayXd det = g.a11.array() * g.a22.array() - g.a12.array().square();
  k.inv11 = g.a22.array() / det;
  k.inv12 = -g.a12.array() / det;
  k.inv22 = g.a11.array() / det;
  k.J.resize(np);
  k.W.resize(np);
  k.n11.resize(np);
  k.n12.resize(np);
  k.n22.resize(np);
  for (int p = 0; p < np; ++p) {
    // Invariants (18) from C = A^{-1} a: tr C = A^{ab} a_ab, det C = det a / det A.
    const double trC = rest_->inv11[p] * g.a11[p] + 2 * rest_->inv12[p] * g.a12[p] + rest_->inv22[p] * g.a22[p];
    const double detC = det[p] / rest_->det[p];
    const double J = std::sqrt(detC);
    const StrainEnergy e = params_.law->energy(trC - 2.0, detC - 1.0);
    // Cauchy tension N^{ab} = (2/J) W1 A^{ab} + 2 J W2 a^{ab}; for Skalak this is eq. (20).
    const double ca = 2.0 * e.W1 / J, cb = 2.0 * J * e.W2;
    k.J[p] = J;
    k.W[p] = e.W;
    k.n11[p] = ca * rest_->inv11[p] + cb * k.inv11[p];
    k.n12[p] = ca * rest_->inv12[p] + cb * k.inv12[p];
    k.n22[p] = ca * rest_->inv22[p] + cb * k.inv22[p];
  }
  k.dbend.resize(np, 4);
  k.dbend.col(0) = k.inv11.array() * g.b11.array() + k.inv12.array() * g.b12.array() - rest_->b11.array();
  k.dbend.col(1) = k.inv11.array() * g.b12.array() + k.inv12.array() * g.b22.array() - rest_->b12.array();
  k.dbend.col(2) = k.inv12.array() * g.b11.array() + k.inv22.array() * g.b12.array() - rest_->b21.array();
  k.dbend.col(3) = k.inv12.array() * g.b12.array() + k.inv22.array() * g.b22.array() - rest_->b22.array();
  return k;
}

namespace {

// Cartesian components (column 3 i + j) of T^{ab} a_a (x) a_b.
Eigen::MatrixXd cartesian_tensor(const SurfaceGeometry& g, const Eigen::VectorXd& t11,
                                 const Eigen::VectorXd& t12, const Eigen::VectorXd& t21,
                                 const Eigen::VectorXd& t22) {
  Eigen::MatrixXd T(g.size(), 9);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      T.col(3 * i + j) = t11.array() * g.a1.col(i).array() * g.a1.col(j).array() +
                         t12.array() * g.a1.col(i).array() * g.a2.col(j).array() +
                         t21.array() * g.a2.col(i).array() * g.a1.col(j).array() +
                         t22.array() * g.a2.col(i).array() * g.a2.col(j).array();
    }
  }
  return T;
}

double bending_energy(const Eigen::MatrixXd& dbend, const Eigen::VectorXd& area_weight, double eb) {
  // (E_B / 2) integral db^a_b db^b_a dA.
  const Eigen::ArrayXd sq = dbend.col(0).array().square() + 2.0 * dbend.col(1).array() * dbend.col(2).array() +
                            dbend.col(3).array().square();
  return 0.5 * eb * (sq * area_weight.array()).sum();
}

}  // namespace

double Membrane::elastic_energy(const SHCoeffs& x) const {
  const SurfaceGeometry g = surface_geometry(x, *grids_->m_grid);
  const Kinematics k = kinematics(g);
  // dA_ref = dA / J.
  double e = (k.W.array() * g.area_weight.array() / k.J.array()).sum();
  if (params_.bending_modulus > 0) e += bending_energy(k.dbend, g.area_weight, params_.bending_modulus);
  return e;
}

MembraneState Membrane::compute(const SHCoeffs& x) const {
  const SHTransform& tm = *grids_->m_grid;
  const SHTransform& tn = *grids_->n_grid;
  const int N = grids_->order;
  if (x.order() > N || x.components() != 3) {
    throw std::invalid_argument("Membrane::compute: need 3-component coefficients of order <= " + std::to_string(N));
  }
  const SurfaceGeometry g = surface_geometry(x, tm);
  const Kinematics k = kinematics(g);
  const double eb = params_.bending_modulus;

  Eigen::MatrixXd T = cartesian_tensor(g, k.n11, k.n12, k.n12, k.n22);
  MembraneState s;
  s.elastic_energy = (k.W.array() * g.area_weight.array() / k.J.array()).sum();
  if (eb > 0) {
    // M^{ab} = M^a_c a^{cb}, M^a_b = -E_B (b^a_b - b^{aR}_b)  (21).
    const Eigen::VectorXd m11 = -eb * (k.dbend.col(0).array() * k.inv11.array() + k.dbend.col(1).array() * k.inv12.array());
    const Eigen::VectorXd m12 = -eb * (k.dbend.col(0).array() * k.inv12.array() + k.dbend.col(1).array() * k.inv22.array());
    const Eigen::VectorXd m21 = -eb * (k.dbend.col(2).array() * k.inv11.array() + k.dbend.col(3).array() * k.inv12.array());
    const Eigen::VectorXd m22 = -eb * (k.dbend.col(2).array() * k.inv12.array() + k.dbend.col(3).array() * k.inv22.array());
    // Torque balance (22b) sets the antisymmetric part of N to that of K^{ab} = b^a_c M^{cb}.
    // It vanishes when b^R commutes with b (a spherical reference) but not for a biconcave one.
    const Eigen::ArrayXd bm11 = k.dbend.col(0).array(), bm12 = k.dbend.col(1).array(),
                         bm21 = k.dbend.col(2).array(), bm22 = k.dbend.col(3).array();
    // b^a_c = db^a_c + b^{aR}_c (current mixed curvature).
    const Eigen::ArrayXd c11 = bm11 + rest_->b11.array(), c12 = bm12 + rest_->b12.array(),
                         c21 = bm21 + rest_->b21.array(), c22 = bm22 + rest_->b22.array();
    const Eigen::ArrayXd k12 = c11 * m12.array() + c12 * m22.array();
    const Eigen::ArrayXd k21 = c21 * m11.array() + c22 * m21.array();
    const Eigen::VectorXd anti = 0.5 * (k12 - k21);  // N^{12} - N^{21} = K^{12} - K^{21}
    T += cartesian_tensor(g, Eigen::VectorXd::Zero(g.size()), anti, -anti, Eigen::VectorXd::Zero(g.size()));
    // Transverse shear (22a): Q^b = M^{ab}_|a, the tangential part of div_s M.
    const Eigen::MatrixXd divm = surface_divergence(cartesian_tensor(g, m11, m12, m21, m22), g, tm);
    const Eigen::VectorXd qn = (divm.array() * g.normal.array()).rowwise().sum();
    const Eigen::MatrixXd q = divm - qn.asDiagonal() * g.normal;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) T.col(3 * i + j).array() += q.col(i).array() * g.normal.col(j).array();
    }
    s.elastic_energy += bending_energy(k.dbend, g.area_weight, eb);
  }
  // Local equilibrium (23): div_s T + f = 0.
  const Eigen::MatrixXd f = -surface_divergence(T, g, tm);

  s.traction = tm.analyze(f, N);
  s.traction_grid = tn.synthesize(s.traction);

  // Diagnostics, filtered to n < N and shown on the N grid: J_S and the principal tensions,
  // eigenvalues of the symmetric tension in an orthonormal tangent frame (e1, e2).
  Eigen::MatrixXd diag(g.size(), 3);
  for (int p = 0; p < g.size(); ++p) {
    const Eigen::Vector3d a1 = g.a1.row(p), a2 = g.a2.row(p), n = g.normal.row(p);
    const Eigen::Vector3d e1 = a1.normalized(), e2 = n.cross(e1);
    // Components of a_a along e_i, then S_ij = N^{ab} (a_a . e_i)(a_b . e_j).
    Eigen::Matrix2d c;
    c << a1.dot(e1), a1.dot(e2), a2.dot(e1), a2.dot(e2);
    Eigen::Matrix2d nab;
    nab << k.n11[p], k.n12[p], k.n12[p], k.n22[p];
    const Eigen::Matrix2d S = c.transpose() * nab * c;
    const double mean = 0.5 * (S(0, 0) + S(1, 1));
    const double radius = std::hypot(0.5 * (S(0, 0) - S(1, 1)), S(0, 1));
    diag.row(p) << k.J[p], mean + radius, mean - radius;
  }
  const Eigen::MatrixXd filtered = tn.synthesize(tm.analyze(diag, N));
  s.dilatation = filtered.col(0);
  s.principal_tension = filtered.rightCols(2);
  return s;
}

}  // namespace rbcflow
