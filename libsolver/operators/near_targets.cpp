#include "near_targets.h"

#include "geometry/surface_projection.h"

namespace rbcflow {

NearTargets find_near_targets(const CellQuadratureGeometry& cell, const Eigen::MatrixXd& points,
                              const std::optional<PeriodicBox>& box, int skip_begin, int skip_end) {
  NearTargets out;
  const SourceNodes& nodes = cell.nodes();
  const double near = cell.near_distance();
  const Eigen::Vector3d lo = nodes.x.colwise().minCoeff(), hi = nodes.x.colwise().maxCoeff();
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const SphGrid& grid = cell.grids().n_grid->grid();
  for (int r = 0; r < points.rows(); ++r) {
    if (r >= skip_begin && r < skip_end) continue;
    Eigen::Vector3d x0 = points.row(r).transpose();
    if (box) {
      const Eigen::Vector3d L = box->lengths();
      x0 -= (L.array() * ((x0 - centre).array() / L.array()).round()).matrix();
    }
    if (((x0 - lo).array() < -near).any() || ((x0 - hi).array() > near).any()) continue;
    Eigen::Index nearest = 0;
    (nodes.x.rowwise() - x0.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
    const int q = static_cast<int>(nearest);
    const SurfaceProjection proj =
        project_onto_surface(cell.coeffs(), x0, grid.theta()[q / grid.n_phi()], grid.phi(q % grid.n_phi()));
    if (proj.distance >= near) continue;
    QuadratureTarget t;
    t.x = x0;
    t.theta = proj.theta;
    t.phi = proj.phi;
    t.distance = proj.distance;
    out.targets.push_back(t);
    out.rows.push_back(r);
  }
  return out;
}

}  // namespace rbcflow
