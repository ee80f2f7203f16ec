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
#include "libsolver/common/periodic_box.h"

namespace rbcflow {

struct NearTargets {
  std::vector<QuadratureTarget> targets;
  std::vector<int> rows;  // the row of `points` each target came from
};

// Rows skip_begin <= row < skip_end are left out (the cell's own nodes in a stacked array).
NearTargets find_near_targets(const CellQuadratureGeometry& cell, const Eigen::MatrixXd& points,
                              const std::optional<PeriodicBox>& box, int skip_begin = 0, int skip_end = 0);

// A cell's own nodes that lie within the near distance of another part of the same surface:
// the two faces at a red cell's dimple (0.3 apart, against a near distance of 0.5 at N = 16), a
// folded rim. The node's singular patch covers its own neighbourhood only; the other part,
// more than kSelfNearAngle patch radii away on the parameter sphere, gets a nearly-singular
// patch centred at the node's projection onto it. At that separation neither patch's window
// reaches where the other's integrand is (nearly) singular, so the two corrections add.
// Rows are row_offset + node.
inline constexpr double kSelfNearAngle = 1.5;
NearTargets find_self_near_targets(const CellQuadratureGeometry& cell, int row_offset = 0);

}  // namespace rbcflow
