#pragma once
// Singular and nearly-singular integration on a spherical-harmonic cell by the floating
// partition of unity (section 5.4, eq. 31-33). For each target the accurate integral is
//   I = I_1 (polar patch around the target or its projection, eq. 33)
//     + I_2 (regular rule (30) with weights (1 - eta)),
// and what this module returns is the correction I - (regular rule over the cell's nodes), so
// that the caller's regular sums (direct, or SPME + real space) stay untouched:
//   correction = I_1 - sum_{nodes in the patch, not the target itself} eta K psi w.
// The accuracy of I_2 is set by how well the grid resolves (1 - eta) K, which varies on the
// patch scale rho_1: the paper's rho_1 = pi / sqrt(N) gives O(h^3); a larger patch (factor)
// is more accurate and costs more points. (Summing I_2 on a finer grid inside a sharp patch
// boundary does not help: the cut is a discontinuity.)
// Everything that depends only on geometry (patch points, interpolation stencils, kernel
// matrices) is built once per time step; apply() is linear in the density and is what every
// GMRES product calls.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "geometry/surface/cell_grids.h"
#include "geometry/surface/sh_surface.h"
#include "libsolver/common/patch_node.h"
#include "libsolver/common/memory_report.h"
#include "libsolver/quadrature/hermite_interpolation.h"
#include "libsolver/quadrature/layer_kernel.h"
#include "libsolver/quadrature/regular_quadrature.h"

namespace rbcflow {

struct QuadratureOptions {
  double patch_radius_factor = 2.0;  // rho_1 = factor * pi / sqrt(N) (the paper: factor 1)
  int radial_points = 0;             // points in rho; 0: default (see default_radial_points)
  int angular_points = 0;            // points in the patch angle; 0: 2 x radial
  int spline_refinement = 2;         // Hermite grid (r N + 1) x 2 r N
  double near_factor = 1.0;          // nearly singular when d < near_factor sqrt(h)
  // Keep the patch stencils (a point's offsets in its Hermite cell), the patch kernels and the
  // double layer's node entries in single precision between products (LayerCorrection): a
  // third of their memory, the largest part of a step's. They are computed in double; a
  // correction then differs by a relative ~1e-7 (float rounding, summed over a patch), an
  // order below the Ewald and GMRES tolerances of a run (1e-6), measured in
  // tests/libsolver/quadrature/test_singular_quadrature.cpp (CompactTables..., FoldedPatchNodes...).
  bool compact_tables = true;
};
int default_radial_points(int order);

// A target of one source cell's corrections.
struct QuadratureTarget {
  Eigen::Vector3d x;      // the target point
  double theta = 0, phi = 0;  // patch centre: the node's parameters, or the projection's
  double distance = 0;    // 0 for points on the surface, |x - projection| otherwise
  int self_node = -1;     // the cell's node that coincides with x (on-surface targets), or -1
};

// A cell's mesh size h = sqrt(A / N^2) from its area A on the N grid, and the reach of its
// nearly-singular corrections beyond its nodes: the near distance near_factor sqrt(h) plus h
// (the nodes lie within h of the surface; near_targets.cpp). CellQuadratureGeometry's, from
// the area alone (a cell's halo before its geometry is built; cell_halo.h).
inline double cell_mesh_size(double area, int order) { return std::sqrt(area) / order; }
inline double cell_near_distance(double mesh_size, const QuadratureOptions& options) {
  return options.near_factor * std::sqrt(mesh_size);
}
inline double cell_near_reach(double area, int order, const QuadratureOptions& options) {
  const double h = cell_mesh_size(area, order);
  return cell_near_distance(h, options) + h;
}

// Geometry of one cell shared by all its corrections: the nodes, the Hermite data of x and of
// the area vector J n = (a1 x a2) / sin(theta) (dA n = J n dOmega), and the patch radius.
class CellQuadratureGeometry {
 public:
  CellQuadratureGeometry(const SHCoeffs& x, std::shared_ptr<const CellGrids> grids,
                         const QuadratureOptions& options = {});

  const SHCoeffs& coeffs() const { return x_; }
  const CellGrids& grids() const { return *grids_; }
  const QuadratureOptions& options() const { return options_; }
  const SourceNodes& nodes() const { return nodes_; }
  double patch_radius() const { return rho1_; }
  double mesh_size() const { return h_; }              // h = sqrt(A / N^2)
  double near_distance() const { return near_; }       // targets closer than this need a patch
  // On-surface targets: every node of the cell.
  std::vector<QuadratureTarget> node_targets() const;

  // The Hermite data of a density given at the nodes (nodes x 3), through its expansion of
  // order N: what LayerCorrection::apply interpolates at the patch points. One per density and
  // cell serves all the cell's corrections.
  HermiteData patch_data(const Eigen::MatrixXd& density) const;

  // x and J n at a point of the parameter sphere (Hermite interpolation; phi_shift as in
  // HermiteInterpolator::interpolate).
  void geometry_at(const HermiteStencil& s, Eigen::Vector3d& x, Eigen::Vector3d& jn, int phi_shift = 0) const;
  const HermiteInterpolator& interpolator() const { return *interp_; }
  std::size_t memory_bytes() const;  // its arrays (the shared grids and interpolator not counted)

 private:
  SHCoeffs x_, jn_;
  std::shared_ptr<const CellGrids> grids_;
  QuadratureOptions options_;
  SourceNodes nodes_;
  std::shared_ptr<const HermiteInterpolator> interp_;
  HermiteData x_data_, jn_data_;
  double rho1_ = 0, h_ = 0, near_ = 0;
};

// The regular rule's nodes of a cell of order <= N (positions, unit normals and area weights on
// the N grid), as CellQuadratureGeometry holds them: for the cells whose corrections another
// rank builds (operators/cell_layers.h).
SourceNodes cell_nodes(const SHCoeffs& x, const CellGrids& grids);

// Which of the regular rule's nodes inside a patch (other than the target's own) the correction
// removes the share eta K w of, by their distance d from the target. The caller's regular sum
// is direct (every node) or an Ewald real-space sum of the screened kernel over the pairs
// closer than its cutoff.
struct NodeShares {
  // d < fold: left to the caller's regular sum, which weights them by 1 - eta itself (folded();
  // an Ewald real-space sum whose cutoff and nearest image reach them: spme/real_space_sum.h
  // PairShares). 0: the correction removes them.
  double fold = 0.0;
  // d >= reach: the caller's sum has no such pair (the real-space cutoff), so there is no share
  // to remove; the patch integral still covers them. Removing one would add -eta K w of a kernel
  // that the Ewald split truncates there, an error of the order of the truncation's own.
  double reach = std::numeric_limits<double>::infinity();
};

class LayerCorrection {
 public:
  LayerCorrection(std::shared_ptr<const CellQuadratureGeometry> cell, LayerKernel kernel,
                  std::vector<QuadratureTarget> targets, NodeShares shares = {});
  // The single- and double-layer corrections of the same targets, built together: the patch
  // geometry (points, interpolated x and J n, the regular rule's nodes inside) is computed once.
  static std::pair<std::unique_ptr<LayerCorrection>, std::unique_ptr<LayerCorrection>> single_and_double(
      const std::shared_ptr<const CellQuadratureGeometry>& cell, double xi_single, double xi_double,
      const std::vector<QuadratureTarget>& targets, std::array<NodeShares, 2> shares = {});

  int num_targets() const { return static_cast<int>(targets_.size()); }
  const std::vector<QuadratureTarget>& targets() const { return targets_; }
  // The patch nodes of target t whose share the caller removes (NodeShares::fold), held as long
  // as the correction (the pair shares of the caller's real-space sums point to them).
  std::span<const PatchNode> folded(int t) const {
    if (folded_offsets_.empty()) return {};
    return {folded_.data() + folded_offsets_[t], static_cast<std::size_t>(folded_offsets_[t + 1] - folded_offsets_[t])};
  }
  // Correction at every target for the density given at the cell's nodes (nodes x 3); the
  // patch sees its expansion of order N (exact for the band-limited densities of the solver).
  Eigen::MatrixXd apply(const Eigen::MatrixXd& density) const;
  // The same with the patch's density given by its own expansion (order <= 2N), for densities
  // that are not band-limited to N, such as the normal in the identities of section 8.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& density, const SHCoeffs& patch_density) const;
  // The same with the patch's density as Hermite data (CellQuadratureGeometry::patch_data).
  Eigen::MatrixXd apply(const Eigen::MatrixXd& density, const HermiteData& patch_data) const;

  // Adds "<prefix>: patch stencils" (unless with_stencils is false: the single- and
  // double-layer corrections of single_and_double share them), "patch kernels", "node entries",
  // "folded nodes".
  void report_memory(MemoryReport& report, const std::string& prefix, bool with_stencils = true) const;

 private:
  struct Unbuilt {};
  LayerCorrection(std::shared_ptr<const CellQuadratureGeometry> cell, LayerKernel kernel,
                  std::vector<QuadratureTarget> targets, NodeShares shares, Unbuilt);
  // Fills stencils_, patch_k_ and nodes_ of corrections that share their cell and targets.
  static void build(std::span<LayerCorrection* const> corrections);

  // Where the patch points of each target sit on the Hermite grid, shared by the single- and
  // double-layer corrections of the same targets. The node targets of one ring of the grid
  // share one table (their patches differ by a rotation about the axis: a shift in phi by
  // whole Hermite cells); any other target has a table of its own. Every table holds the whole
  // polar rule, points_per_table points, all in one array allocated without initialisation.
  struct PatchStencils {
    std::size_t points_per_table = 0, tables = 0;
    // table b: [b, b + 1) * points_per_table, in one of three forms: double (compact_tables
    // off), single-precision weights (compact_tables, every table a ring's) or the points'
    // places only (compact_tables, tables of single targets)
    std::unique_ptr<HermiteStencil[]> points;
    std::unique_ptr<FloatHermiteStencil[]> floats;
    std::unique_ptr<CompactHermiteStencil[]> compact;
    std::vector<int> table, phi_shift;  // per target
    template <class Stencil>
    std::span<const Stencil> of_target(const std::unique_ptr<Stencil[]>& all, int t) const {
      return {all.get() + static_cast<std::size_t>(table[t]) * points_per_table, points_per_table};
    }
    std::size_t memory_bytes() const;
  };
  using PackedKernel = std::array<double, 6>;  // symmetric 3x3 kernel times weights: xx, xy, xz, yy, yz, zz
  using CompactKernel = std::array<float, 6>;
  template <class Kernel>
  struct NodeEntry {
    int node;
    Kernel k;
  };
  // The correction at target t for the density's Hermite data, with either precision's tables.
  template <class Stencil, class Kernel, class NodeKernel>
  Eigen::Vector3d correction_at(int t, const std::unique_ptr<Stencil[]>& stencils, const Kernel* kernels,
                                const NodeEntry<NodeKernel>* node_entries, const Eigen::MatrixXd& density,
                                const HermiteData& data) const;
  std::shared_ptr<const CellQuadratureGeometry> cell_;
  LayerKernel kernel_;
  std::vector<QuadratureTarget> targets_;
  NodeShares shares_;
  std::shared_ptr<const PatchStencils> stencils_;
  // Per target t, entries [offsets[t], offsets[t + 1]) of each array (one allocation each
  // rather than one per target).
  std::vector<PackedKernel> patch_k_;  // in the order of the target's table (compact_tables off)
  std::vector<CompactKernel> patch_kf_;  // the same in single precision (compact_tables on)
  // Nodes in the patch: -eta K w. In single precision for the double layer with compact_tables
  // (the single layer's cancel against its real-space sum: rounded, the layer moved by 1.5e-6).
  std::vector<NodeEntry<PackedKernel>> nodes_;
  std::vector<NodeEntry<CompactKernel>> nodes_f_;
  std::vector<PatchNode> folded_;      // nodes in the patch left to the caller
  std::vector<std::int64_t> patch_offsets_, node_offsets_, folded_offsets_;
};

// Free-space layer potential of one cell at its own nodes: regular rule + corrections.
// (patch_density: as in LayerCorrection::apply; empty means the order-N expansion.)
Eigen::MatrixXd free_space_layer_on_nodes(const std::shared_ptr<const CellQuadratureGeometry>& cell,
                                          Layer layer, const Eigen::MatrixXd& density,
                                          const SHCoeffs& patch_density = {});

}  // namespace rbcflow
