#include "real_space_sum.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "libsolver/kernels/ewald_real_kernel.h"

namespace rbcflow {
namespace {

void check_rows(const PointField& field, int n, const char* what) {
  if (field.rows() != n)
    throw std::invalid_argument(std::string("real-space Ewald sum: ") + what + " has " +
                                std::to_string(field.rows()) + " rows for " + std::to_string(n) +
                                " sources");
}

// Densities gathered into the neighbour list's sorted source order, `width` numbers per source.
std::vector<double> sorted_densities(const NeighborList& pairs,
                                     std::initializer_list<const PointField*> fields) {
  const int width = 3 * static_cast<int>(fields.size());
  std::vector<double> out(static_cast<std::size_t>(width) * pairs.n_sources());
  const std::vector<int>& order = pairs.order();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < pairs.n_sources(); ++i) {
    double* o = &out[static_cast<std::size_t>(width) * i];
    for (const PointField* f : fields)
      for (int d = 0; d < 3; ++d) *o++ = (*f)(order[i], d);
  }
  return out;
}

// Two coefficients per pair in `coefficients` (filled now when it is empty, else read).
bool prepare(const NeighborList& pairs, std::vector<double>* coefficients) {
  if (!coefficients) return false;
  const bool fill = coefficients->empty();
  if (fill) coefficients->resize(2 * static_cast<std::size_t>(pairs.n_pairs()));
  return fill;
}

}  // namespace

PointField real_space_single_layer(const NeighborList& pairs, double xi, const PointField& forces,
                                   std::vector<double>* coefficients) {
  check_rows(forces, pairs.n_sources(), "the force field");
  const std::vector<double> f = sorted_densities(pairs, {&forces});
  const EwaldRealKernel kernel(xi);
  const bool fill = prepare(pairs, coefficients);
  double* c = coefficients ? coefficients->data() : nullptr;
  PointField u(pairs.n_targets(), 3);
#pragma omp parallel for schedule(dynamic, 64)
  for (int k = 0; k < pairs.n_targets(); ++k) {
    const int t = pairs.target_order()[k];
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    pairs.for_each_pair(t, [&](std::int64_t i, int s, const Eigen::Vector3d& r) {
      const Eigen::Map<const Eigen::Vector3d> fs(&f[3 * static_cast<std::size_t>(s)]);
      double a, b;  // S^R f = a f + b (r.f) r
      if (c && !fill) {
        a = c[2 * i];
        b = c[2 * i + 1];
      } else {
        const double r2 = r.squaredNorm(), rn = std::sqrt(r2);
        const StokesletSplitCoeffs k2 = kernel.stokeslet_coeffs(rn);
        a = k2.a;
        b = k2.b / r2;
        if (c) {
          c[2 * i] = a;
          c[2 * i + 1] = b;
        }
      }
      acc += a * fs + (b * r.dot(fs)) * r;
    });
    u.row(t) = acc.transpose();
  }
  return u;
}

PointField real_space_double_layer(const NeighborList& pairs, double xi, const PointField& q,
                                   const PointField& normals, std::vector<double>* coefficients) {
  check_rows(q, pairs.n_sources(), "the double-layer density");
  check_rows(normals, pairs.n_sources(), "the normal field");
  const std::vector<double> qn = sorted_densities(pairs, {&q, &normals});
  const EwaldRealKernel kernel(xi);
  const bool fill = prepare(pairs, coefficients);
  double* c = coefficients ? coefficients->data() : nullptr;
  PointField u(pairs.n_targets(), 3);
#pragma omp parallel for schedule(dynamic, 64)
  for (int k = 0; k < pairs.n_targets(); ++k) {
    const int t = pairs.target_order()[k];
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    pairs.for_each_pair(t, [&](std::int64_t i, int s, const Eigen::Vector3d& r) {
      const Eigen::Map<const Eigen::Vector3d> qs(&qn[6 * static_cast<std::size_t>(s)]);
      const Eigen::Map<const Eigen::Vector3d> ns(&qn[6 * static_cast<std::size_t>(s) + 3]);
      double alpha, beta;
      if (c && !fill) {
        alpha = c[2 * i];
        beta = c[2 * i + 1];
      } else {
        const StressletSplitCoeffs k2 = kernel.stresslet_coeffs(r.norm());
        alpha = k2.alpha;
        beta = k2.beta;
        if (c) {
          c[2 * i] = alpha;
          c[2 * i + 1] = beta;
        }
      }
      const double rq = r.dot(qs), rn = r.dot(ns);
      acc += (alpha * rq * rn + beta * qs.dot(ns)) * r + beta * (rn * qs + rq * ns);
    });
    u.row(t) = acc.transpose();
  }
  return u;
}

}  // namespace rbcflow
