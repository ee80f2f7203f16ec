#include "geometry/sph/sph_transform.h"

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include "geometry/sph/fftw_util.h"

namespace rbcflow {
namespace {

using cplx = std::complex<double>;

// Per-thread scratch arrays for FFTW's new-array execution.
struct Scratch {
  FftwBuffer<double> real;
  FftwBuffer<cplx> spec;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

// (A, B) of A cos(m phi) + B sin(m phi) after `dphi` derivatives in phi.
void differentiate_in_phi(int m, int dphi, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
  for (int d = 0; d < dphi; ++d) {
    Eigen::MatrixXd a_new = m * B;
    B = -m * A;
    A.swap(a_new);
  }
}

}  // namespace

struct SHTransform::Plans {
  fftw_plan forward = nullptr;   // r2c: real grid rows -> Fourier coefficients in phi
  fftw_plan backward = nullptr;  // c2r
  std::size_t real_size = 0, spec_size = 0;
  ~Plans() {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (forward) fftw_destroy_plan(forward);
    if (backward) fftw_destroy_plan(backward);
  }
};

SHTransform::SHTransform(int order, SphGrid grid, int max_theta_derivative)
    : order_(order), grid_(std::move(grid)) {
  if (order < 1) throw std::invalid_argument("SHTransform: order must be >= 1");
  if (grid_.n_phi() < 2 * order - 1) {
    throw std::invalid_argument("SHTransform: order " + std::to_string(order) + " needs at least " +
                                std::to_string(2 * order - 1) + " longitudes, grid has " +
                                std::to_string(grid_.n_phi()));
  }
  tables_ = legendre_theta_tables(grid_.theta(), order, max_theta_derivative);
  if (grid_.is_gauss()) {
    analysis_.resize(order);
    const Eigen::VectorXd& w = grid_.weights();
    for (int m = 0; m < order; ++m) {
      // a_nm = 2 / (n_phi (1 + delta_m0)) sum_i w_i Pbar_n^m(x_i) Re F_m(theta_i); b_nm likewise
      // with -Im F_m, F_m the discrete Fourier coefficient of the row theta_i.
      const double scale = 2.0 / (grid_.n_phi() * (m == 0 ? 2.0 : 1.0));
      analysis_[m] = scale * tables_[0][m].transpose() * w.asDiagonal();
    }
  }
}

SHTransform SHTransform::gauss(int order, int max_theta_derivative) {
  return SHTransform(order, SphGrid::gauss(order), max_theta_derivative);
}

SHTransform::~SHTransform() = default;

const SHTransform::Plans& SHTransform::plans(int components) const {
  std::lock_guard<std::mutex> lock(plans_mutex_);
  auto it = plans_.find(components);
  if (it != plans_.end()) return *it->second;

  auto p = std::make_unique<Plans>();
  const int nphi = grid_.n_phi();
  const int nf = nphi / 2 + 1;
  const int howmany = grid_.n_theta() * components;
  p->real_size = static_cast<std::size_t>(howmany) * nphi;
  p->spec_size = static_cast<std::size_t>(howmany) * nf;
  FftwBuffer<double> real(p->real_size);
  FftwBuffer<cplx> spec(p->spec_size);
  {
    std::lock_guard<std::mutex> planner(fftw_planner_mutex());
    int n[1] = {nphi};
    p->forward = fftw_plan_many_dft_r2c(1, n, howmany, real.data(), nullptr, 1, nphi,
                                        reinterpret_cast<fftw_complex*>(spec.data()), nullptr, 1,
                                        nf, FFTW_ESTIMATE);
    p->backward = fftw_plan_many_dft_c2r(1, n, howmany,
                                         reinterpret_cast<fftw_complex*>(spec.data()), nullptr,
                                         1, nf, real.data(), nullptr, 1, nphi, FFTW_ESTIMATE);
  }
  if (!p->forward || !p->backward) throw std::runtime_error("SHTransform: FFTW planning failed");
  return *(plans_[components] = std::move(p));
}

SHCoeffs SHTransform::analyze(const Eigen::MatrixXd& values, int out_order) const {
  if (!grid_.is_gauss()) throw std::logic_error("SHTransform::analyze needs a Gauss grid");
  if (out_order == 0) out_order = order_;
  if (out_order < 1 || out_order > order_) {
    throw std::invalid_argument("SHTransform::analyze: output order " + std::to_string(out_order) +
                                " outside 1.." + std::to_string(order_));
  }
  if (values.rows() != grid_.size()) {
    throw std::invalid_argument("SHTransform::analyze: field has " + std::to_string(values.rows()) +
                                " rows, grid has " + std::to_string(grid_.size()) + " points");
  }
  const int k = static_cast<int>(values.cols());
  const Plans& p = plans(k);
  Scratch& s = scratch();
  s.real.reserve(p.real_size);
  s.spec.reserve(p.spec_size);
  std::copy(values.data(), values.data() + p.real_size, s.real.data());
  fftw_execute_dft_r2c(p.forward, s.real.data(), reinterpret_cast<fftw_complex*>(s.spec.data()));

  const int nt = grid_.n_theta();
  const int nf = grid_.n_phi() / 2 + 1;
  SHCoeffs out(out_order, k);
  Eigen::MatrixXd re(nt, k), im(nt, k);
  for (int m = 0; m < out_order; ++m) {
    for (int c = 0; c < k; ++c) {
      for (int i = 0; i < nt; ++i) {
        const cplx f = s.spec.data()[static_cast<std::size_t>(c * nt + i) * nf + m];
        re(i, c) = f.real();
        im(i, c) = f.imag();
      }
    }
    const int len = out_order - m;
    const auto A = analysis_[m].topRows(len);
    out.values().middleRows(SHCoeffs::cos_offset(out_order, m), len).noalias() = A * re;
    if (m > 0) out.values().middleRows(SHCoeffs::sin_offset(out_order, m), len).noalias() = -(A * im);
  }
  return out;
}

Eigen::MatrixXd SHTransform::synthesize(const SHCoeffs& c, int dtheta, int dphi) const {
  Eigen::MatrixXd out;
  synthesize(c, dtheta, dphi, out);
  return out;
}

void SHTransform::synthesize(const SHCoeffs& c, int dtheta, int dphi, Eigen::MatrixXd& out) const {
  if (c.order() > order_) {
    throw std::invalid_argument("SHTransform::synthesize: coefficients of order " +
                                std::to_string(c.order()) + " exceed the transform's " +
                                std::to_string(order_));
  }
  if (dtheta < 0 || dtheta > max_theta_derivative() || dphi < 0) {
    throw std::invalid_argument("SHTransform::synthesize: derivative order (" +
                                std::to_string(dtheta) + ", " + std::to_string(dphi) +
                                ") not available (max theta derivative " +
                                std::to_string(max_theta_derivative()) + ")");
  }
  const int k = c.components();
  const int nc = c.order();
  const int nt = grid_.n_theta();
  const int nf = grid_.n_phi() / 2 + 1;
  const Plans& p = plans(k);
  Scratch& s = scratch();
  s.real.reserve(p.real_size);
  s.spec.reserve(p.spec_size);
  cplx* spec = s.spec.data();
  std::fill(spec, spec + p.spec_size, cplx(0.0, 0.0));

  Eigen::MatrixXd A(nt, k), B(nt, k);
  for (int m = 0; m < nc; ++m) {
    const int len = nc - m;
    const auto D = tables_[dtheta][m].leftCols(len);
    A.noalias() = D * c.values().middleRows(SHCoeffs::cos_offset(nc, m), len);
    if (m > 0) {
      B.noalias() = D * c.values().middleRows(SHCoeffs::sin_offset(nc, m), len);
    } else {
      B.setZero();
    }
    differentiate_in_phi(m, dphi, A, B);
    // c2r sums X_0 + 2 Re sum_{m>0} X_m e^{i m phi}: X_0 = A_0, X_m = (A_m - i B_m) / 2.
    const double half = (m == 0) ? 1.0 : 0.5;
    for (int comp = 0; comp < k; ++comp) {
      for (int i = 0; i < nt; ++i) {
        spec[static_cast<std::size_t>(comp * nt + i) * nf + m] =
            cplx(half * A(i, comp), -half * B(i, comp));
      }
    }
  }
  fftw_execute_dft_c2r(p.backward, reinterpret_cast<fftw_complex*>(spec), s.real.data());
  out.resize(grid_.size(), k);
  std::copy(s.real.data(), s.real.data() + p.real_size, out.data());
}

Eigen::RowVectorXd sh_evaluate(const SHCoeffs& c, double theta, double phi, int dtheta, int dphi) {
  const int nc = c.order();
  const LegendreTables t = legendre_theta_tables(Eigen::VectorXd::Constant(1, theta), nc, dtheta);
  Eigen::RowVectorXd value = Eigen::RowVectorXd::Zero(c.components());
  for (int m = 0; m < nc; ++m) {
    const int len = nc - m;
    const Eigen::RowVectorXd p = t[dtheta][m].row(0);
    Eigen::MatrixXd A = p * c.values().middleRows(SHCoeffs::cos_offset(nc, m), len);
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(1, c.components());
    if (m > 0) B = p * c.values().middleRows(SHCoeffs::sin_offset(nc, m), len);
    differentiate_in_phi(m, dphi, A, B);
    value += A * std::cos(m * phi) + B * std::sin(m * phi);
  }
  return value;
}

SHJet sh_evaluate_jet(const SHCoeffs& c, double theta, double phi) {
  if (c.components() != 3) throw std::invalid_argument("sh_evaluate_jet: need 3 components");
  const int nc = c.order(), size = legendre_size(nc);
  // Called in every Newton step of every surface projection: no allocation.
  thread_local std::vector<double> legendre;
  legendre.resize(3 * static_cast<std::size_t>(size));
  legendre_theta_point(theta, nc, 2, legendre.data());
  const Eigen::MatrixXd& v = c.values();
  SHJet j;
  j.x = j.x_t = j.x_p = j.x_tt = j.x_tp = j.x_pp = Eigen::Vector3d::Zero();
  const double c1 = std::cos(phi), s1 = std::sin(phi);
  double cm = 1.0, sm = 0.0;  // cos(m phi), sin(m phi) by the angle-addition recurrence
  for (int m = 0; m < nc; ++m) {
    const int len = nc - m, cos_row = SHCoeffs::cos_offset(nc, m), sin_row = SHCoeffs::sin_offset(nc, m);
    Eigen::Vector3d A[3], B[3];  // theta derivative k of the cos and sin parts
    for (int k = 0; k < 3; ++k) {
      const double* p = legendre.data() + k * size + legendre_index(nc, m, m);
      A[k].setZero();
      B[k].setZero();
      for (int i = 0; i < len; ++i) {
        for (int comp = 0; comp < 3; ++comp) A[k][comp] += p[i] * v(cos_row + i, comp);
        if (m > 0)
          for (int comp = 0; comp < 3; ++comp) B[k][comp] += p[i] * v(sin_row + i, comp);
      }
    }
    j.x += cm * A[0] + sm * B[0];
    j.x_t += cm * A[1] + sm * B[1];
    j.x_tt += cm * A[2] + sm * B[2];
    j.x_p += m * (cm * B[0] - sm * A[0]);
    j.x_tp += m * (cm * B[1] - sm * A[1]);
    j.x_pp -= double(m) * m * (cm * A[0] + sm * B[0]);
    const double next = cm * c1 - sm * s1;
    sm = sm * c1 + cm * s1;
    cm = next;
  }
  return j;
}

}  // namespace rbcflow
