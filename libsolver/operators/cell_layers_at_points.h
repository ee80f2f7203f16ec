#pragma once
// The layer integrals of all cells evaluated at points off the cells (the wall nodes in the
// no-slip condition (7)): the same sums as CellLayers (direct in free space; SPME + real
// space in a box, with the linear part of (3) for the double layer), and the nearly-singular
// correction for every point closer to a cell than its near distance. Built once per time
// step from the step's CellLayers; the products are linear in the densities. On several ranks,
// as CellLayers: each rank sums its owned cells as sources, and a product is the ranks' sum.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cell_layers.h"

namespace rbcflow {

// The grid of the layers of `nodes` cell nodes at `points` points in a periodic domain, for the
// single layer (EwaldKernel::stokeslet) or the double layer (stresslet), from `grid_cache`:
// CellLayersAtPoints's, known before it is built (the slabs of a step's halo). Collective.
std::shared_ptr<const SpmeGrid> cell_layers_at_points_grid(const LayerDomain& domain, EwaldKernel kernel, long nodes,
                                                           long points, SpmeGridCache* grid_cache);

class CellLayersAtPoints {
 public:
  // single_layer_density: as in CellLayers, the one single-layer density of the step (its
  // traction, in the layers' held layout), whose single layer is computed here with its
  // corrections and plan freed after use; single_layer then takes that matrix only (the same
  // object, read only here).
  // `bring_density` is called with the layers' halo_with(slabs()) before it is read.
  CellLayersAtPoints(const CellLayers& layers, const Eigen::MatrixXd& points,
                     const Eigen::MatrixXd* single_layer_density = nullptr, const DensityHalo& bring_density = {});
  ~CellLayersAtPoints();

  int num_points() const { return static_cast<int>(points_.rows()); }
  int near_points() const;  // (point, cell) pairs that needed the nearly-singular correction
  // "<prefix> near corrections: ...", "<prefix> Ewald single/double: ..." (memory_report.h).
  void report_memory(MemoryReport& report, const std::string& prefix) const;

  // Densities at the layers' held rows (CellLayers::nodes()'s: every cell's on one rank; the
  // rows of the cells not read may hold anything); the results have one row per point.
  // single_layer throws std::logic_error for another matrix than the constructor's, if given.
  Eigen::MatrixXd single_layer(const Eigen::MatrixXd& f) const;
  Eigen::MatrixXd double_layer(const Eigen::MatrixXd& u) const;
  // This rank's parts of the two (its cells as sources, its slab of the grid): the layers are
  // the sums of the ranks' parts, which a caller that needs only some rows sums itself.
  Eigen::MatrixXd single_layer_part(const Eigen::MatrixXd& f) const;
  Eigen::MatrixXd double_layer_part(const Eigen::MatrixXd& u) const;
  // This rank's planes of its plans' grids split over the ranks: a part reads the densities of
  // the owned cells and of the nodes whose stencils reach these (CellLayers::halo_with).
  const std::vector<SlabPlanes>& slabs() const { return slabs_; }

 private:
  struct Near {
    std::unique_ptr<LayerCorrection> single, double_;
    std::vector<int> rows;
  };
  Eigen::MatrixXd corrections(Layer layer, const Eigen::MatrixXd& density) const;
  Eigen::MatrixXd regular_single_layer(const Eigen::MatrixXd& f) const;  // this rank's part
  SourceNodes owned_sources() const;  // the nodes of the cells this rank owns
  // The owned cells' rows of held node data (the layers' nodes, CellLayers::nodes).
  template <class Matrix>
  auto owned_nodes(const Matrix& held) const {
    return held.middleRows(layers_.owned_nodes().begin, layers_.owned().size() * layers_.nodes_per_cell());
  }

  const CellLayers& layers_;
  Eigen::MatrixXd points_;
  std::vector<Near> near_;  // per cell
  std::unique_ptr<EwaldPlan> single_plan_, double_plan_;
  const Eigen::MatrixXd* single_density_ = nullptr;  // read only while built, then its address compared
  std::optional<Eigen::MatrixXd> single_part_;        // this rank's part, of single_density_
  std::vector<SlabPlanes> slabs_;
};

}  // namespace rbcflow
