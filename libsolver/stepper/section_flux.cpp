#include "section_flux.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "geometry/surface/surface_projection.h"
#include "geometry/surface/triangle_mesh.h"
#include "libsolver/operators/cell_layers_at_points.h"

namespace rbcflow {
namespace {

PointField wrapped(const Eigen::Matrix<double, Eigen::Dynamic, 3>& x, const PeriodicBox& box) {
  PointField p(x.rows(), 3);
  for (int i = 0; i < x.rows(); ++i) p.row(i) = box.wrap(x.row(i).transpose()).transpose();
  return p;
}

// The image of d nearest the origin.
Eigen::Vector3d nearest_image(const Eigen::Vector3d& d, const PeriodicBox& box) {
  return box.wrap(d + 0.5 * box.lengths()) - 0.5 * box.lengths();
}

// Whether y (the image of a point nearest the cell) is inside the cell. Points farther from
// the grid triangulation than its spacing are decided by the winding number of the triangles;
// nearer ones, where the chords can put a point on the wrong side, by the sign of the distance
// to the spectral surface (the foot point by Newton from the nearest grid node).
bool inside_cell(const SHSurface& shape, const TriangleMesh& mesh, const SphGrid& grid, double spacing,
                 const Eigen::Vector3d& y) {
  int nearest = 0;
  const double d = std::sqrt((mesh.points.rowwise() - y.transpose()).rowwise().squaredNorm().minCoeff(&nearest));
  if (d > spacing) return winding_number(mesh, y) > 0.5;
  double theta = 0, phi = 0;
  if (nearest == grid.size() + 1) {
    theta = std::numbers::pi;
  } else if (nearest < grid.size()) {
    theta = grid.theta()[nearest / grid.n_phi()];
    phi = grid.phi(nearest % grid.n_phi());
  }
  const SurfaceProjection p = project_onto_surface(shape.coeffs(), y, theta, phi);
  return p.converged ? p.signed_distance < 0 : winding_number(mesh, y) > 0.5;
}

// 1 for the points inside a cell (only points within the cell's bounding sphere are tested, at
// their image nearest the cell's centre).
Eigen::VectorXi inside_cells(const PointField& points, const CellsAtStep& cells, const PeriodicBox& box) {
  Eigen::VectorXd inside = Eigen::VectorXd::Zero(points.rows());
  const SphGrid& grid = cells.grid->grid();
  const OwnedRange& owned = cells.layers->owned();
  if (static_cast<int>(cells.own_shapes->size()) != owned.size())
    throw std::logic_error("section fluxes: not the shapes of the layers' own cells");
  for (int c = owned.begin; c < owned.end; ++c) {
    const SHSurface& shape = (*cells.own_shapes)[static_cast<std::size_t>(c - owned.begin)];
    const TriangleMesh mesh = shape.triangulate(*cells.grid);
    const Eigen::Vector3d centre = mesh.points.colwise().mean().transpose();
    const double radius = (mesh.points.rowwise() - centre.transpose()).rowwise().norm().maxCoeff();
    const double spacing = std::sqrt(surface_area(shape.geometry(*cells.grid))) / grid.n_theta();
    for (int i = 0; i < points.rows(); ++i) {
      const Eigen::Vector3d d = nearest_image(points.row(i).transpose() - centre, box);
      if (d.norm() <= radius && inside_cell(shape, mesh, grid, spacing, centre + d)) inside[i] = 1;
    }
  }
  cells.layers->domain().ranks.sum(inside);  // each rank tests its own cells
  return (inside.array() > 0).cast<int>();
}

}  // namespace

SectionFluxMeter::SectionFluxMeter(const WallCoupling& wall, std::vector<std::vector<SectionQuadrature>> branches)
    : box_(wall.box()) {
  for (auto& sections : branches) {
    if (sections.empty()) throw std::invalid_argument("SectionFluxMeter: a branch without a section");
    std::vector<Candidate> candidates;
    for (auto& q : sections) {
      PointField p = wrapped(q.points, box_);
      WallOperator op = wall.operator_at(p);
      candidates.push_back({std::move(q), std::move(p), std::move(op)});
    }
    branches_.push_back(std::move(candidates));
  }
}

std::optional<long> SectionFluxMeter::points_per_step() const {
  long n = 0;
  for (const std::vector<Candidate>& candidates : branches_) {
    const long m = candidates.front().points.rows();
    for (const Candidate& c : candidates)
      if (c.points.rows() != m) return std::nullopt;
    n += m;
  }
  return n;
}

int SectionFluxMeter::clearest(int b, const CellLayers* layers) const {
  const std::vector<Candidate>& candidates = branches_[b];
  if (!layers || candidates.size() == 1) return 0;
  // Each rank measures the clearance of its own cells' nodes; the least over the ranks.
  const int np = layers->nodes_per_cell();
  const auto nodes = layers->nodes().x.middleRows(layers->owned_nodes().begin, layers->owned().size() * np);
  int best = 0;
  double best_clearance = -1;
  for (int k = 0; k < static_cast<int>(candidates.size()); ++k) {
    const SectionQuadrature& q = candidates[k].section;
    const Eigen::Vector3d centre = q.points.colwise().mean().transpose();  // the disk's centre
    const double radius = (q.points.rowwise() - centre.transpose()).rowwise().norm().maxCoeff();
    double clearance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < nodes.rows(); ++i) {
      const Eigen::Vector3d d = nearest_image(nodes.row(i).transpose() - centre, box_);
      const double axial = d.dot(q.normal), radial = (d - axial * q.normal).norm();
      clearance = std::min(clearance, radial <= radius ? std::abs(axial) : std::hypot(axial, radial - radius));
    }
    clearance = layers->domain().ranks.min(clearance);
    if (clearance > best_clearance) {
      best_clearance = clearance;
      best = k;
    }
  }
  return best;
}

std::vector<double> SectionFluxMeter::fluxes(const Eigen::Vector3d& mean_velocity, const PointField& wall_force,
                                             const CellsAtStep* cells) {
  const bool with_cells = cells != nullptr;
  std::vector<Candidate*> chosen;
  int n = 0;
  for (int b = 0; b < num_branches(); ++b) {
    chosen.push_back(&branches_[b][clearest(b, with_cells ? cells->layers : nullptr)]);
    n += static_cast<int>(chosen.back()->points.rows());
  }
  PointField points(n, 3), u(n, 3);
  int row = 0;
  for (Candidate* c : chosen) {
    const int m = static_cast<int>(c->points.rows());
    points.middleRows(row, m) = c->points;
    u.middleRows(row, m) = WallCoupling::velocity_at(c->wall_at_points, wall_force);
    row += m;
  }
  u.rowwise() += mean_velocity.transpose();
  if (with_cells) {
    constexpr double kPi = std::numbers::pi;
    const double lambda = cells->viscosity_ratio;
    const CellLayersAtPoints at(*cells->layers, points, cells->traction, cells->bring_densities);
    slabs_ = at.slabs();
    u -= at.single_layer(*cells->traction) / (8 * kPi);
    if (lambda != 1.0) u += (1 - lambda) / (8 * kPi) * at.double_layer(*cells->velocity);
    const Eigen::VectorXi inside = inside_cells(points, *cells, box_);
    for (int i = 0; i < u.rows(); ++i)
      if (inside[i]) u.row(i) /= lambda;
  }
  std::vector<double> flux;
  row = 0;
  for (const Candidate* c : chosen) {
    const int m = static_cast<int>(c->points.rows());
    flux.push_back(c->section.weights.dot(u.middleRows(row, m) * c->section.normal));
    row += m;
  }
  return flux;
}

}  // namespace rbcflow
