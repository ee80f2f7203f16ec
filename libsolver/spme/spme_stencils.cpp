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

template <int C>
void SpmeStencils::spread_point(int i, const double* density, double* grid) const {
  const int* f = &first_[3 * static_cast<std::size_t>(i)];
  const double* w = &weights_[3 * static_cast<std::size_t>(p_) * i];
  const double* rho = density + C * static_cast<std::size_t>(order_[i]);
  int index[3][kMaxSplineOrder];
  for (int d = 0; d < 3; ++d)
    for (int j = 0; j < p_; ++j) index[d][j] = f[d] + j < K_[d] ? f[d] + j : f[d] + j - K_[d];
  double w_rho[kMaxSplineOrder][C];
  for (int c = 0; c < p_; ++c)
    for (int k = 0; k < C; ++k) w_rho[c][k] = w[2 * p_ + c] * rho[k];
  for (int a = 0; a < p_; ++a) {
    for (int b = 0; b < p_; ++b) {
      const double wab = w[a] * w[p_ + b];
      double* row =
          grid + C * ((static_cast<std::size_t>(index[0][a]) * K_[1] + index[1][b]) * K_[2]);
      for (int c = 0; c < p_; ++c) {
        double* g = row + C * static_cast<std::size_t>(index[2][c]);
        for (int k = 0; k < C; ++k) g[k] += wab * w_rho[c][k];
      }
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
    int index[3][kMaxSplineOrder];
    for (int d = 0; d < 3; ++d)
      for (int j = 0; j < p_; ++j) index[d][j] = f[d] + j < K_[d] ? f[d] + j : f[d] + j - K_[d];
    double acc[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < p_; ++a) {
      for (int b = 0; b < p_; ++b) {
        const double wab = w[a] * w[p_ + b];
        const double* row =
            grid + 3 * ((static_cast<std::size_t>(index[0][a]) * K_[1] + index[1][b]) * K_[2]);
        for (int c = 0; c < p_; ++c) {
          const double* g = row + 3 * static_cast<std::size_t>(index[2][c]);
          const double wt = wab * w[2 * p_ + c];
          acc[0] += wt * g[0];
          acc[1] += wt * g[1];
          acc[2] += wt * g[2];
        }
      }
    }
    for (int k = 0; k < 3; ++k) out(order_[i], k) = acc[k];
  }
}

template void SpmeStencils::spread<3>(const double*, double*) const;
template void SpmeStencils::spread<6>(const double*, double*) const;

}  // namespace rbcflow
