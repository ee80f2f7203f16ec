#pragma once
// The points that are nearly singular for one cell's layer integrals: those closer than the
// cell's near distance (d < near_factor sqrt(h), section 5.4) to its surface, each with its
// projection onto the surface (Newton on the spectral surface, seeded by the closest point of
// the grid triangulation from a CGAL AABB tree),
// the centre of the floating partition of unity. In a periodic box each point is taken at
// its periodic image nearest the cell.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "libsolver/quadrature/singular_quadrature.h"
#include "libsolver/spme/periodic_box.h"

namespace rbcflow {

struct NearTargets {
  std::vector<QuadratureTarget> targets;
  std::vector<int> rows;  // the row of `points` each target came from
};

// Rows skip_begin <= row < skip_end are left out (the cell's own nodes in a stacked array).
NearTargets find_near_targets(const CellQuadratureGeometry& cell, const Eigen::MatrixXd& points,
                              const std::optional<PeriodicBox>& box, int skip_begin = 0, int skip_end = 0);

}  // namespace rbcflow
