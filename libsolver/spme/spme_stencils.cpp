#include "spme_stencils.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "bspline.h"
#include "libsolver/common/memory_report.h"

namespace rbcflow {

SpmeStencils::SpmeStencils(const SpmeGrid& grid, const PointField& points)
    : K_{grid.size(0), grid.size(1), grid.size(2)},
      p_(grid.order()),
      first_plane_(grid.first_plane()),
      planes_(grid.planes()),
      row_stride_(grid.row_stride()),
      slab_points_(grid.slab_points()),
      points_(static_cast<int>(points.rows())) {
  const int n = points_;
  const PeriodicBox& box = grid.box();
  std::vector<int> first(3 * static_cast<std::size_t>(n));
  std::vector<double> weights(3 * static_cast<std::size_t>(p_) * n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d x = box.wrap(points.row(i).transpose());
    for (int d = 0; d < 3; ++d) {
      const double u = x[grid.axis(d)] * K_[d] / box.length(grid.axis(d));
      const int cell = std::min(static_cast<int>(std::floor(u)), K_[d] - 1);
      double w[kMaxSplineOrder];
      bspline_weights(p_, u - cell, w);  // w[j] belongs to index cell - j
      first[3 * static_cast<std::size_t>(i) + d] = (cell - (p_ - 1) + K_[d]) % K_[d];
      double* out = &weights[(3 * static_cast<std::size_t>(i) + d) * p_];
      for (int j = 0; j < p_; ++j) out[j] = w[p_ - 1 - j];
    }
  }

  // An even number of slabs, each at least p - 1 planes wide (one slab if K_0 < 2 (p - 1)):
  // spreading runs the slabs of one colour (even or odd) in parallel.
  const int n_slabs = std::max(1, 2 * (K_[0] / (2 * (p_ - 1))));
  const auto slab_plane = [&](int s) { return static_cast<int>(static_cast<std::int64_t>(s) * K_[0] / n_slabs); };
  std::vector<int> slab_of_plane(K_[0]);
  for (int s = 0; s < n_slabs; ++s)
    for (int plane = slab_plane(s); plane < slab_plane(s + 1); ++plane) slab_of_plane[plane] = s;

  // The points that touch this rank's planes (all of them on an undivided grid), slab by slab so
  // that each slab is a contiguous range, and within a slab by tiles of kTile x kTile stencil
  // origins across the other two directions: consecutive points then share most of their
  // stencils' grid rows, which stay in cache.
  const auto touches_planes = [&](int i) {
    for (int a = 0; a < p_; ++a)
      if (plane_row((first[3 * static_cast<std::size_t>(i)] + a) % K_[0], 0) >= 0) return true;
    return false;
  };
  for (int i = 0; i < n; ++i)
    if (touches_planes(i)) order_.push_back(i);
  const int kept = size();
  constexpr int kTile = 16;
  const auto key = [&](int i) {
    const int* f = &first[3 * static_cast<std::size_t>(i)];
    const int tile = (f[1] / kTile) * ((K_[2] + kTile - 1) / kTile) + f[2] / kTile;
    return std::tuple(slab_of_plane[f[0]], tile, (static_cast<std::int64_t>(f[0]) * K_[1] + f[1]) * K_[2] + f[2]);
  };
  std::sort(order_.begin(), order_.end(), [&](int a, int b) { return key(a) < key(b); });
  first_.resize(3 * static_cast<std::size_t>(kept));
  weights_.resize(3 * static_cast<std::size_t>(p_) * kept);
  for (int i = 0; i < kept; ++i) {
    const std::size_t from = static_cast<std::size_t>(order_[i]);
    std::copy_n(&first[3 * from], 3, &first_[3 * static_cast<std::size_t>(i)]);
    std::copy_n(&weights[3 * p_ * from], 3 * p_, &weights_[3 * static_cast<std::size_t>(p_) * i]);
  }

  slab_begin_.resize(n_slabs + 1);
  for (int s = 0; s <= n_slabs; ++s) {
    slab_begin_[s] = static_cast<int>(
        std::partition_point(order_.begin(), order_.end(),
                             [&](int i) { return slab_of_plane[first[3 * static_cast<std::size_t>(i)]] < s; }) -
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
    if (plane_row(i0, 0) < 0) continue;
    for (int b = 0; b < p_; ++b) {
      const int i1 = f[1] + b < K_[1] ? f[1] + b : f[1] + b - K_[1];
      const double wab = w[a] * w[p_ + b];
      double* row = grid + C * plane_row(i0, i1);
      add_scaled(row + C * f[2], wab, w_rho, C * run);
      add_scaled(row, wab, w_rho + C * run, C * (p_ - run));
    }
  }
}

template <int C>
void SpmeStencils::spread(const double* density, double* grid) const {
  const std::size_t total = C * slab_points_;
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
  out.resize(points_, 3);
  if (size() < points_) out.setZero();  // points that do not touch this rank's planes
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
      if (plane_row(i0, 0) < 0) continue;
      for (int b = 0; b < p_; ++b) {
        const int i1 = f[1] + b < K_[1] ? f[1] + b : f[1] + b - K_[1];
        const double wab = w[a] * w[p_ + b];
        const double* row = grid + 3 * plane_row(i0, i1);
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

SpmeStencils::SpreadingMatrix SpmeStencils::spreading_matrix(const Eigen::SparseMatrix<double, Eigen::RowMajor>& map) const {
  if (map.rows() != points_)
    throw std::invalid_argument("SPME spreading matrix: the map has " + std::to_string(map.rows()) + " rows for " +
                                std::to_string(points_) + " points");
  // Column n: the points of unknown n that touch this rank's planes (all on a whole grid).
  Eigen::SparseMatrix<double> by_unknown = map;
  std::vector<int> rank(points_, -1);
  for (int k = 0; k < size(); ++k) rank[order_[k]] = k;
  by_unknown.prune([&](Eigen::Index row, Eigen::Index, double) { return rank[row] >= 0; });
  const int m = static_cast<int>(map.cols());
  const auto wrap = [&](int i, int d) { return ((i % K_[d]) + K_[d]) % K_[d]; };
  std::vector<std::vector<std::pair<int, double>>> columns(m);
#pragma omp parallel
  {
    std::vector<double> box;
#pragma omp for schedule(dynamic, 16)
    for (int n = 0; n < m; ++n) {
      Eigen::SparseMatrix<double>::InnerIterator first_point(by_unknown, n);
      if (!first_point) continue;
      // The unknown's stencils in unwrapped grid indices from its first point's: a box of
      // e_0 x e_1 x e_2 grid points accumulates them.
      const int* base = &first_[3 * static_cast<std::size_t>(rank[first_point.row()])];
      std::array<int, 3> lo{0, 0, 0}, hi{p_, p_, p_};
      const auto offset = [&](int k, int d) {
        int o = first_[3 * static_cast<std::size_t>(k) + d] - base[d];
        if (o > K_[d] / 2) o -= K_[d];
        if (o < -K_[d] / 2) o += K_[d];
        return o;
      };
      for (Eigen::SparseMatrix<double>::InnerIterator it(by_unknown, n); it; ++it)
        for (int d = 0; d < 3; ++d) {
          const int o = offset(rank[it.row()], d);
          lo[d] = std::min(lo[d], o);
          hi[d] = std::max(hi[d], o + p_);
        }
      const int e0 = hi[0] - lo[0], e1 = hi[1] - lo[1], e2 = hi[2] - lo[2];
      box.assign(static_cast<std::size_t>(e0) * e1 * e2, 0.0);
      for (Eigen::SparseMatrix<double>::InnerIterator it(by_unknown, n); it; ++it) {
        const int k = rank[it.row()];
        const double* w = &weights_[3 * static_cast<std::size_t>(p_) * k];
        const int o0 = offset(k, 0) - lo[0], o1 = offset(k, 1) - lo[1], o2 = offset(k, 2) - lo[2];
        for (int a = 0; a < p_; ++a)
          for (int b = 0; b < p_; ++b) {
            const double wab = it.value() * w[a] * w[p_ + b];
            double* row = &box[(static_cast<std::size_t>(o0 + a) * e1 + (o1 + b)) * e2 + o2];
            for (int c = 0; c < p_; ++c) row[c] += wab * w[2 * p_ + c];
          }
      }
      // Grid indices wrapped; a box wider than the grid folds onto itself: merge equal indices.
      std::vector<std::pair<int, double>>& column = columns[n];
      for (int a = 0; a < e0; ++a)
        for (int b = 0; b < e1; ++b)
          for (int c = 0; c < e2; ++c) {
            const double v = box[(static_cast<std::size_t>(a) * e1 + b) * e2 + c];
            if (v == 0.0) continue;
            const std::ptrdiff_t row = plane_row(wrap(base[0] + lo[0] + a, 0), wrap(base[1] + lo[1] + b, 1));
            if (row < 0) continue;  // another rank's plane
            column.emplace_back(static_cast<int>(row + wrap(base[2] + lo[2] + c, 2)), v);
          }
      std::sort(column.begin(), column.end());
      std::size_t kept = 0;
      for (std::size_t i = 0; i < column.size(); ++i) {
        if (kept > 0 && column[kept - 1].first == column[i].first) {
          column[kept - 1].second += column[i].second;
        } else {
          column[kept++] = column[i];
        }
      }
      column.resize(kept);
    }
  }
  Eigen::SparseMatrix<double> s(static_cast<Eigen::Index>(slab_points_), m);
  Eigen::VectorXi sizes(m);
  for (int n = 0; n < m; ++n) sizes[n] = static_cast<int>(columns[n].size());
  s.reserve(sizes);
  for (int n = 0; n < m; ++n) {
    for (const auto& [g, v] : columns[n]) s.insert(g, n) = v;
    std::vector<std::pair<int, double>>().swap(columns[n]);
  }
  return SpreadingMatrix(s);
}

template void SpmeStencils::spread<1>(const double*, double*) const;
template void SpmeStencils::spread<3>(const double*, double*) const;
template void SpmeStencils::spread<6>(const double*, double*) const;

std::size_t SpmeStencils::memory_bytes() const {
  return heap_bytes(order_) + heap_bytes(first_) + heap_bytes(weights_) + heap_bytes(slab_begin_);
}

}  // namespace rbcflow
