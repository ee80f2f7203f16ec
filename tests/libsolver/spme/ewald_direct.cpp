#include "tests/libsolver/spme/ewald_direct.h"

#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "libsolver/kernels/ewald_kernels.h"

namespace rbcflow {
namespace {

using Complex = std::complex<double>;
constexpr double pi = std::numbers::pi;

// sum over sources s and lattice vectors n with 0 < |r| < r_c, r = x_s + n L - x_t, of pair(s, r).
template <class Pair>
PointField real_sum(const PeriodicBox& box, double cutoff, const PointField& sources,
                    const PointField& targets, Pair pair) {
  const double eps = 1e-12 * std::cbrt(box.volume());  // as NeighborList
  std::array<int, 3> images{};
  for (int d = 0; d < 3; ++d) images[d] = static_cast<int>(std::ceil(cutoff / box.length(d)));
  const Eigen::Vector3d L = box.lengths();
  PointField u(targets.rows(), 3);
#pragma omp parallel for schedule(dynamic, 16)
  for (Eigen::Index t = 0; t < targets.rows(); ++t) {
    const Eigen::Vector3d xt = box.wrap(targets.row(t).transpose());
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    for (Eigen::Index s = 0; s < sources.rows(); ++s) {
      const Eigen::Vector3d d = box.wrap(sources.row(s).transpose()) - xt;
      for (int a = -images[0]; a <= images[0]; ++a)
        for (int b = -images[1]; b <= images[1]; ++b)
          for (int c = -images[2]; c <= images[2]; ++c) {
            const Eigen::Vector3d r = d + Eigen::Vector3d(a * L[0], b * L[1], c * L[2]);
            const double r2 = r.squaredNorm();
            if (r2 < cutoff * cutoff && r2 > eps * eps) acc += pair(s, r);
          }
    }
    u.row(t) = acc.transpose();
  }
  return u;
}

// exp(i 2 pi n x_d / L_d) for n = -n_max_d .. n_max_d: table[d][(n + n_max_d) * points + i].
struct PhaseTable {
  std::array<std::vector<Complex>, 3> phase;
  std::array<int, 3> n_max;
  Eigen::Index points;

  PhaseTable(const PeriodicBox& box, const std::array<int, 3>& n_max_, const PointField& x)
      : n_max(n_max_), points(x.rows()) {
    for (int d = 0; d < 3; ++d) {
      phase[d].resize((2 * n_max[d] + 1) * static_cast<std::size_t>(points));
      for (int n = -n_max[d]; n <= n_max[d]; ++n)
        for (Eigen::Index i = 0; i < points; ++i)
          phase[d][(n + n_max[d]) * points + i] =
              std::polar(1.0, 2.0 * pi * n * x(i, d) / box.length(d));
    }
  }
  // exp(i k.x_i) for k = 2 pi n / L.
  Complex operator()(const std::array<int, 3>& n, Eigen::Index i) const {
    return phase[0][(n[0] + n_max[0]) * points + i] * phase[1][(n[1] + n_max[1]) * points + i] *
           phase[2][(n[2] + n_max[2]) * points + i];
  }
};

// (1/V) sum_{k != 0, |k| <= k_c} K^F(k) . [sum_s rho_s e^{i k.x_s}] e^{-i k.x_t}, summed over
// half of k-space and doubled (real result). density(s) gives C numbers; kernel(k, S) gives
// the three complex components of K^F(k) . S.
template <int C, class Density, class Kernel>
PointField fourier_sum(const PeriodicBox& box, double k_cut, const PointField& sources,
                       const PointField& targets, Density density, Kernel kernel) {
  std::array<int, 3> n_max{};
  for (int d = 0; d < 3; ++d)
    n_max[d] = static_cast<int>(std::floor(k_cut * box.length(d) / (2 * pi)));
  std::vector<std::array<int, 3>> modes;
  for (int a = 0; a <= n_max[0]; ++a)
    for (int b = -n_max[1]; b <= n_max[1]; ++b)
      for (int c = -n_max[2]; c <= n_max[2]; ++c) {
        if (!(a > 0 || b > 0 || (b == 0 && c > 0))) continue;  // half space, k != 0
        const Eigen::Vector3d k(2 * pi * a / box.length(0), 2 * pi * b / box.length(1),
                                2 * pi * c / box.length(2));
        if (k.norm() <= k_cut) modes.push_back({a, b, c});
      }
  const PhaseTable source_phase(box, n_max, sources), target_phase(box, n_max, targets);
  std::vector<std::array<Complex, 3>> v(modes.size());
#pragma omp parallel for schedule(dynamic, 8)
  for (std::size_t m = 0; m < modes.size(); ++m) {
    std::array<Complex, C> S{};
    for (Eigen::Index s = 0; s < sources.rows(); ++s) {
      const Complex e = source_phase(modes[m], s);
      const std::array<double, C> rho = density(s);
      for (int c = 0; c < C; ++c) S[c] += rho[c] * e;
    }
    const Eigen::Vector3d k(2 * pi * modes[m][0] / box.length(0),
                            2 * pi * modes[m][1] / box.length(1),
                            2 * pi * modes[m][2] / box.length(2));
    v[m] = kernel(k, S);
  }
  PointField u(targets.rows(), 3);
  const double scale = 2.0 / box.volume();
#pragma omp parallel for schedule(static)
  for (Eigen::Index t = 0; t < targets.rows(); ++t) {
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    for (std::size_t m = 0; m < modes.size(); ++m) {
      const Complex e = std::conj(target_phase(modes[m], t));
      for (int c = 0; c < 3; ++c) acc[c] += (v[m][c] * e).real();
    }
    u.row(t) = scale * acc.transpose();
  }
  return u;
}

void check_rows(const PointField& field, const PointField& sources, const char* what) {
  if (field.rows() != sources.rows())
    throw std::invalid_argument(std::string("direct Ewald sum: ") + what +
                                " must have one row per source");
}

}  // namespace

EwaldDirect::EwaldDirect(const PeriodicBox& box, double xi)
    : EwaldDirect(box, xi, 6.5 / xi, 13.0 * xi) {}

EwaldDirect::EwaldDirect(const PeriodicBox& box, double xi, double real_cutoff,
                         double fourier_cutoff)
    : box_(box), xi_(xi), real_cutoff_(real_cutoff), fourier_cutoff_(fourier_cutoff) {
  if (!(xi > 0.0 && real_cutoff > 0.0 && fourier_cutoff > 0.0))
    throw std::invalid_argument("direct Ewald sum: xi and both cutoffs must be positive");
}

PointField EwaldDirect::real_single_layer(const PointField& sources, const PointField& forces,
                                          const PointField& targets) const {
  check_rows(forces, sources, "forces");
  return real_sum(box_, real_cutoff_, sources, targets,
                  [&](Eigen::Index s, const Eigen::Vector3d& r) {
                    return ewald_real_stokeslet_apply(r, xi_, forces.row(s).transpose());
                  });
}

PointField EwaldDirect::real_double_layer(const PointField& sources, const PointField& q,
                                          const PointField& normals,
                                          const PointField& targets) const {
  check_rows(q, sources, "the density");
  check_rows(normals, sources, "normals");
  return real_sum(
      box_, real_cutoff_, sources, targets, [&](Eigen::Index s, const Eigen::Vector3d& r) {
        return ewald_real_stresslet_apply(r, xi_, q.row(s).transpose(), normals.row(s).transpose());
      });
}

PointField EwaldDirect::fourier_single_layer(const PointField& sources, const PointField& forces,
                                             const PointField& targets) const {
  check_rows(forces, sources, "forces");
  const auto density = [&](Eigen::Index s) {
    return std::array<double, 3>{forces(s, 0), forces(s, 1), forces(s, 2)};
  };
  const auto kernel = [&](const Eigen::Vector3d& k, const std::array<Complex, 3>& S) {
    const Eigen::Vector3d re = ewald_fourier_stokeslet_apply(
        k, xi_, Eigen::Vector3d(S[0].real(), S[1].real(), S[2].real()));
    const Eigen::Vector3d im = ewald_fourier_stokeslet_apply(
        k, xi_, Eigen::Vector3d(S[0].imag(), S[1].imag(), S[2].imag()));
    return std::array<Complex, 3>{Complex(re[0], im[0]), Complex(re[1], im[1]),
                                  Complex(re[2], im[2])};
  };
  return fourier_sum<3>(box_, fourier_cutoff_, sources, targets, density, kernel);
}

PointField EwaldDirect::fourier_double_layer(const PointField& sources, const PointField& q,
                                             const PointField& normals,
                                             const PointField& targets) const {
  check_rows(q, sources, "the density");
  check_rows(normals, sources, "normals");
  // M_jk = q_j n_k, all nine components.
  const auto density = [&](Eigen::Index s) {
    std::array<double, 9> m{};
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) m[3 * j + k] = q(s, j) * normals(s, k);
    return m;
  };
  // T^F : M = sum_j T^F : (e_j (row j of M)) and T^F : (q n) = i v (ewald_kernels.h).
  const auto kernel = [&](const Eigen::Vector3d& k, const std::array<Complex, 9>& M) {
    Eigen::Vector3d re = Eigen::Vector3d::Zero(), im = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
      re += ewald_fourier_stresslet_apply(
          k, xi_, e, Eigen::Vector3d(M[3 * j].real(), M[3 * j + 1].real(), M[3 * j + 2].real()));
      im += ewald_fourier_stresslet_apply(
          k, xi_, e, Eigen::Vector3d(M[3 * j].imag(), M[3 * j + 1].imag(), M[3 * j + 2].imag()));
    }
    // i (re + i im) = -im + i re
    return std::array<Complex, 3>{Complex(-im[0], re[0]), Complex(-im[1], re[1]),
                                  Complex(-im[2], re[2])};
  };
  return fourier_sum<9>(box_, fourier_cutoff_, sources, targets, density, kernel);
}

PointField EwaldDirect::single_layer(const PointField& sources, const PointField& forces,
                                     const PointField& targets) const {
  return real_single_layer(sources, forces, targets) +
         fourier_single_layer(sources, forces, targets);
}

PointField EwaldDirect::double_layer(const PointField& sources, const PointField& q,
                                     const PointField& normals, const PointField& targets) const {
  return real_double_layer(sources, q, normals, targets) +
         fourier_double_layer(sources, q, normals, targets);
}

}  // namespace rbcflow
