#pragma once
// The smooth part of the periodic single- and double-layer sums by SPME (section 5.2) for
// fixed source and target positions: stencils computed once, so that a product (every GMRES
// iteration) costs spreading + FFT + influence + FFT + interpolation. The grid-sized work
// arrays live for one product (work_bytes()).
//
//   single_layer: u(x_t) = (1/V) sum_{k != 0} S^F(k) . sum_s f_s e^{i k.(x_s - x_t)}
//   double_layer: u_i(x_t) = (1/V) sum_{k != 0} sum_s T^F_ijk(k) q_s,j n_s,k e^{i k.(x_s - x_t)}
// (docs/references.md section 2; densities carry their quadrature weights). A source that is also
// a target contributes its smooth self-term, as it must (only the real-space sum skips r = 0).
//
// Products record their stage timings: one thread at a time per plan (each product is itself
// OpenMP-parallel). Several plans may share one SpmeGrid.
#include <chrono>
#include <memory>

#include "geometry/sph/fftw_util.h"
#include "libsolver/common/periodic_box.h"
#include "spme_grid.h"
#include "spme_stencils.h"

namespace rbcflow {

// Wall-clock seconds of the stages of the last product.
struct SpmeTimings {
  double spreading = 0.0, fft = 0.0, influence = 0.0, interpolation = 0.0;
};

class SpmePlan {
 public:
  SpmePlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources,
           const PointField& targets);
  // Targets are the sources (the stencils are shared).
  SpmePlan(std::shared_ptr<const SpmeGrid> grid, const PointField& points);

  const SpmeGrid& grid() const { return *grid_; }
  int n_sources() const { return sources_->points(); }
  int n_targets() const { return targets_->points(); }

  // forces: one row per source; returns one row per target. Throws on a size mismatch.
  PointField single_layer(const PointField& forces);
  // q (the density, weights included) and normals: one row per source.
  PointField double_layer(const PointField& q, const PointField& normals);
  // single_layer(map x) for `spreading` = sources().spreading_matrix(map): x one row per
  // unknown of the map.
  PointField single_layer(const SpmeStencils::SpreadingMatrix& spreading, const PointField& x);

  const SpmeStencils& sources() const { return *sources_; }
  // Stencils (source and target, once when shared), and the work arrays a product of the layer
  // with `components` (3: single, 6: double) allocates for its duration: plans applied one
  // after the other share that memory through the allocator rather than each keeping its own.
  std::size_t stencil_bytes() const;
  std::size_t work_bytes(int components) const;

  // How double_layer transforms the off-diagonal half of its density (xy, xz, yz): the three
  // components together in an array of 3 grids (the default: 48 bytes a grid point with the
  // velocity's array), or lean, one at a time in an array of one grid (32 bytes a grid point;
  // its transforms take up to 1.5x as long: docs/performance.md), for a memory budget.
  void transform_lean(bool lean) { lean_ = lean; }

  const SpmeTimings& timings() const { return timings_; }

 private:
  // The single layer of the forces spread into the real grids of `grid` (spreading begun at
  // t): transforms, influence function, interpolation, in place.
  PointField convolve_stokeslet(WorkArray& grid, std::chrono::steady_clock::time_point t);
  // Backward FFT of `velocity` in place and interpolation to the targets.
  PointField transform_and_interpolate(WorkArray& velocity);

  std::shared_ptr<const SpmeGrid> grid_;
  std::shared_ptr<const SpmeStencils> sources_, targets_;
  SpmeTimings timings_;
  bool lean_ = false;
};

}  // namespace rbcflow
