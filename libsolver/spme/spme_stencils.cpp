#include "spme_stencils.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "bspline.h"

namespace rbcflow {

SpmeStencils::SpmeStencils(const SpmeGrid& grid, const PointField& points)
    : K_{grid.size(0), grid.size(1), grid.size(2)}, p_(grid.order()) {
  const int n = static_cast<int>(points.rows());
  const PeriodicBox& box = grid.box();
  std::vector<int> first(3 * static_cast<std::size_t>(n));
  std::vector<double> weights(3 * static_cast<std::size_t>(p_) * n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d x = box.wrap(points.row(i).transpose());
    for (int d = 0; d < 3; ++d) {
      const double u = x[d] * K_[d] / box.length(d);
      const int cell = std::min(static_cast<int>(std::floor(u)), K_[d] - 1);
      double w[kMaxSplineOrder];
      bspline_weights(p_, u - cell, w);  // w[j] belongs to index cell - j
      first[3 * static_cast<std::size_t>(i) + d] = (cell - (p_ - 1) + K_[d]) % K_[d];
      double* out = &weights[(3 * static_cast<std::size_t>(i) + d) * p_];
      for (int j = 0; j < p_; ++j) out[j] = w[p_ - 1 - j];
    }
  }

  // Sort by first grid index (slab-major), so that each slab is a contiguous range.
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  const auto key = [&](int i) {
    const int* f = &first[3 * static_cast<std::size_t>(i)];
    return (static_cast<std::int64_t>(f[0]) * K_[1] + f[1]) * K_[2] + f[2];
  };
  std::sort(order_.begin(), order_.end(), [&](int a, int b) { return key(a) < key(b); });
  first_.resize(first.size());
  weights_.resize(weights.size());
  for (int i = 0; i < n; ++i) {
    const std::size_t from = static_cast<std::size_t>(order_[i]);
    std::copy_n(&first[3 * from], 3, &first_[3 * static_cast<std::size_t>(i)]);
    std::copy_n(&weights[3 * p_ * from], 3 * p_, &weights_[3 * static_cast<std::size_t>(p_) * i]);
  }

  // An even number of slabs, each at least p - 1 planes wide (one slab if K_0 < 2 (p - 1)).
  const int n_slabs = std::max(1, 2 * (K_[0] / (2 * (p_ - 1))));
  slab_begin_.resize(n_slabs + 1);
  for (int s = 0; s <= n_slabs; ++s) {
    const int plane = static_cast<int>(static_cast<std::int64_t>(s) * K_[0] / n_slabs);
    slab_begin_[s] = static_cast<int>(
        std::partition_point(
            order_.begin(), order_.end(),
            [&](int i) { return first[3 * static_cast<std::size_t>(i)] < plane; }) -
        order_.begin());
  }
}

namespace {

// The innermost direction in at most two contiguous runs of grid points: n first nodes from the
// stencil's first index, the rest from index 0 when the stencil wraps around the grid.
int first_run(int first, int order, int size) { return std::min(order, size - first); }

// y[m] += a x[m], m < n: contiguous, vectorised.
inline void add_scaled(double* __restrict__ y, double a, const double* __restrict__ x, int n) {
  for (int m = 0; m < n; ++m) y[m] += a * x[m];
}

}  // namespace

template <int C>
void SpmeStencils::spread_point(int i, const double* density, double* grid) const {
  const int* f = &first_[3 * static_cast<std::size_t>(i)];
  const double* w = &weights_[3 * static_cast<std::size_t>(p_) * i];
  const double* rho = density + C * static_cast<std::size_t>(order_[i]);
  // w_rho[C c + k] = w_3(c) rho_k over the innermost direction.
  double w_rho[C * kMaxSplineOrder];
  for (int c = 0; c < p_; ++c)
    for (int k = 0; k < C; ++k) w_rho[C * c + k] = w[2 * p_ + c] * rho[k];
  const int run = first_run(f[2], p_, K_[2]);
  for (int a = 0; a < p_; ++a) {
    const int i0 = f[0] + a < K_[0] ? f[0] + a : f[0] + a - K_[0];
    for (int b = 0; b < p_; ++b) {
      const int i1 = f[1] + b < K_[1] ? f[1] + b : f[1] + b - K_[1];
      const double wab = w[a] * w[p_ + b];
      double* row = grid + C * ((static_cast<std::size_t>(i0) * K_[1] + i1) * K_[2]);
      add_scaled(row + C * f[2], wab, w_rho, C * run);
      add_scaled(row, wab, w_rho + C * run, C * (p_ - run));
    }
  }
}

template <int C>
void SpmeStencils::spread(const double* density, double* grid) const {
  const std::size_t total = C * static_cast<std::size_t>(K_[0]) * K_[1] * K_[2];
#pragma omp parallel for schedule(static)
  for (std::size_t g = 0; g < total; ++g) grid[g] = 0.0;
  const int n_slabs = static_cast<int>(slab_begin_.size()) - 1;
  if (n_slabs == 1) {
    for (int i = 0; i < size(); ++i) spread_point<C>(i, density, grid);
    return;
  }
  for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(dynamic, 1)
    for (int s = colour; s < n_slabs; s += 2)
      for (int i = slab_begin_[s]; i < slab_begin_[s + 1]; ++i) spread_point<C>(i, density, grid);
  }
}

void SpmeStencils::interpolate(const double* grid, PointField& out) const {
  out.resize(size(), 3);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < size(); ++i) {
    const int* f = &first_[3 * static_cast<std::size_t>(i)];
    const double* w = &weights_[3 * static_cast<std::size_t>(p_) * i];
    const int run = first_run(f[2], p_, K_[2]);
    // sums[3 c + k] = sum_ab w_1(a) w_2(b) grid_k(a, b, c), then weighted along the innermost
    // direction.
    double sums[3 * kMaxSplineOrder] = {};
    for (int a = 0; a < p_; ++a) {
      const int i0 = f[0] + a < K_[0] ? f[0] + a : f[0] + a - K_[0];
      for (int b = 0; b < p_; ++b) {
        const int i1 = f[1] + b < K_[1] ? f[1] + b : f[1] + b - K_[1];
        const double wab = w[a] * w[p_ + b];
        const double* row = grid + 3 * ((static_cast<std::size_t>(i0) * K_[1] + i1) * K_[2]);
        add_scaled(sums, wab, row + 3 * f[2], 3 * run);
        add_scaled(sums + 3 * run, wab, row, 3 * (p_ - run));
      }
    }
    for (int k = 0; k < 3; ++k) {
      double acc = 0.0;
      for (int c = 0; c < p_; ++c) acc += w[2 * p_ + c] * sums[3 * c + k];
      out(order_[i], k) = acc;
    }
  }
}

template void SpmeStencils::spread<3>(const double*, double*) const;
template void SpmeStencils::spread<6>(const double*, double*) const;

}  // namespace rbcflow
