#pragma once
// B-spline stencils of one point set on an SPME grid: the p^3 grid points and weights of each
// point, computed once per geometry, and the two grid operations that use them (Essmann et al.
// 1995, eq. 4.6): spreading point densities to the grid and interpolating grid values back.
//
// A point at grid coordinate u_d = x_d / h_d = floor(u_d) + t_d touches the grid indices
// floor(u_d) - j (mod K_d) with weight M_p(t_d + j), j = 0 .. p-1, in each direction.
//
// Spreading is parallel without races by colouring: the points are sorted into slabs along the
// first grid direction, each at least p - 1 grid planes wide, an even number of them around
// the periodic grid; slabs of one parity never write to the same grid plane.
//
// On a grid split over ranks (SpmeGrid::distributed()) the stencils are those of the points
// that touch this rank's planes, and spreading and interpolation use only those planes: the
// grid arrays are the rank's slab, interpolation gives its part of each point's value (zero
// for a point that does not touch the slab).
#include <Eigen/SparseCore>
#include <array>
#include <cstddef>
#include <vector>

#include "libsolver/common/periodic_box.h"
#include "spme_grid.h"

namespace rbcflow {

class SpmeStencils {
 public:
  SpmeStencils(const SpmeGrid& grid, const PointField& points);

  int size() const { return static_cast<int>(order_.size()); }  // points with a stencil here
  int points() const { return points_; }                        // the caller's points
  // The caller's points with a stencil here (all but those off this rank's slab), in the
  // stencils' order.
  const std::vector<int>& point_indices() const { return order_; }
  std::size_t memory_bytes() const;

  // grid[C * g + c] = sum_points W_point(g) density[C * point + c]: `density` holds C
  // interleaved numbers per point in the caller's order; `grid` is overwritten.
  template <int C>
  void spread(const double* density, double* grid) const;

  // out(point, c) = sum_g W_point(g) grid[3 * g + c], one row per point of the caller.
  void interpolate(const double* grid, PointField& out) const;

  // The spreading of densities that are a fixed linear map of other unknowns (point i's density
  // = sum_n map(i, n) x_n) as one matrix S, grid points (the index g of spread()) x unknowns:
  // spread(map x) = S x. For points that never move and whose densities come from fewer
  // unknowns (the wall's Gauss points from its nodal densities, 7 per triangle), S holds the
  // stencils merged per unknown and its product reads less than spreading point by point.
  // On a grid split over ranks, S has a row per point of this rank's slab (its real array,
  // padding included). Throws std::invalid_argument when map has not one row per point.
  using SpreadingMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  SpreadingMatrix spreading_matrix(const Eigen::SparseMatrix<double, Eigen::RowMajor>& map) const;

 private:
  template <int C>
  void spread_point(int i, const double* density, double* grid) const;

  // Row of grid plane i0 (global index), row j of it, in the grid array: -1 when the plane
  // is not this rank's.
  std::ptrdiff_t plane_row(int i0, int j) const {
    const int local = i0 - first_plane_;
    if (local < 0 || local >= planes_) return -1;
    return (static_cast<std::ptrdiff_t>(local) * K_[1] + j) * row_stride_;
  }

  std::array<int, 3> K_;
  int p_;
  int first_plane_ = 0, planes_ = 0, row_stride_ = 0;  // this rank's part of the grid
  std::size_t slab_points_ = 0;                          // SpmeGrid::slab_points()
  int points_ = 0;
  std::vector<int> order_;       // stencils are stored sorted: entry i is point order_[i]
  std::vector<int> first_;       // 3 per point: first grid index (mod K_d) of the stencil
  std::vector<double> weights_;  // 3 p per point: ascending grid index in each direction
  std::vector<int> slab_begin_;  // points of slab s: [slab_begin_[s], slab_begin_[s + 1])
};

extern template void SpmeStencils::spread<1>(const double*, double*) const;
extern template void SpmeStencils::spread<3>(const double*, double*) const;
extern template void SpmeStencils::spread<6>(const double*, double*) const;

}  // namespace rbcflow
