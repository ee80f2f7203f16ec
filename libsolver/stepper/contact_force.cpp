#include "libsolver/stepper/contact_force.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "libsolver/stepper/cell_proximity.h"
#include "libsolver/stepper/held_shapes.h"

namespace rbcflow {
namespace {

// The separation below which t is held at its value there (18 kappa): surfaces that close
// further are the kinematic removal's (h_s), and a law finite everywhere keeps one step's
// force bounded where a point overshoots.
constexpr double kFloor = 1.0 / 20.0;

double floored(const ContactLaw& law, double d) { return std::max(d, kFloor * law.range); }

}  // namespace

double ContactLaw::traction(double separation) const {
  if (!active() || separation >= range) return 0.0;
  const double d = floored(*this, separation);
  return strength * (range - d) * (range - d) / (range * d);
}

double contact_potential(const ContactLaw& law, double separation) {
  if (!law.active() || separation >= law.range) return 0.0;
  const double r = law.range, d = floored(law, separation);
  // Below the floor t is constant: the potential grows linearly there.
  const double below = (d - separation) * law.traction(d);
  return law.strength / r * (r * r * std::log(r / d) - 2.0 * r * (r - d) + 0.5 * (r * r - d * d)) + below;
}

Eigen::MatrixXd contact_force_density(const std::vector<SHCoeffs>& cells, const std::vector<int>& targets,
                                      const SHTransform& grid_transform, const Eigen::Vector3d& period,
                                      const WallDistance* wall, const ContactLaw& law, ContactReport& report) {
  const Eigen::Index np = grid_transform.grid().size();
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(targets.size()) * np, 3);
  report = {};
  if (!law.active() || targets.empty()) return g;
  // The held cells, numbered compactly; the neighbourhood of their bounding spheres.
  std::vector<int> held, compact(cells.size(), -1);
  for (int c = 0; c < static_cast<int>(cells.size()); ++c) {
    if (!shape_held(cells[c])) continue;
    compact[c] = static_cast<int>(held.size());
    held.push_back(c);
  }
  std::vector<CellView> views(held.size());
#pragma omp parallel for schedule(dynamic)
  for (std::size_t i = 0; i < held.size(); ++i) views[i] = cell_view(cells[held[i]], grid_transform);
  const Neighbourhood near = find_neighbours(views, period, law.range);
  std::vector<char> tree_needed(held.size(), 0);
  for (const int a : targets) {
    if (compact[a] < 0) throw std::logic_error("contact_force_density: a target's shape is not held");
    for (const Neighbour& nb : near.near[compact[a]]) tree_needed[nb.b] = 1;
  }
#pragma omp parallel for schedule(dynamic)
  for (std::size_t i = 0; i < held.size(); ++i)
    if (tree_needed[i]) build_tree(views[i], cells[held[i]], grid_transform);

  std::vector<char> near_cell(targets.size(), 0), near_wall(targets.size(), 0);
  std::vector<double> largest(targets.size(), 0.0), closest(targets.size(), report.min_separation);
#pragma omp parallel for schedule(dynamic)
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const CellView& a = views[compact[targets[k]]];
    auto rows = g.middleRows(static_cast<Eigen::Index>(k) * np, np);
    for (const Neighbour& nb : near.near[compact[targets[k]]]) {
      const CellView& b = views[nb.b];
      for (Eigen::Index p = 0; p < np; ++p) {
        const Eigen::Vector3d q = a.points.row(p).transpose() - nb.offset;  // in b's own frame
        const std::optional<SurfaceProjection> s =
            project_within(b, cells[held[nb.b]], grid_transform.grid(), q, law.range);
        if (!s || s->signed_distance >= law.range) continue;
        rows.row(p) += law.traction(s->signed_distance) * s->normal.transpose();
        closest[k] = std::min(closest[k], s->signed_distance);
        near_cell[k] = 1;
      }
    }
    if (wall && wall->closest(a.centre).signed_distance < a.radius + law.range) {
      for (Eigen::Index p = 0; p < np; ++p) {
        const WallDistance::Query w = wall->closest(a.points.row(p).transpose());
        if (w.signed_distance >= law.range) continue;
        rows.row(p) += law.traction(w.signed_distance) * w.normal.transpose();
        closest[k] = std::min(closest[k], w.signed_distance);
        near_wall[k] = 1;
      }
    }
    largest[k] = rows.rowwise().norm().maxCoeff();
  }
  for (std::size_t k = 0; k < targets.size(); ++k) {
    report.cells_near_cells += near_cell[k];
    report.cells_near_wall += near_wall[k];
    report.cells_in_range += near_cell[k] || near_wall[k];
    report.max_traction = std::max(report.max_traction, largest[k]);
    report.min_separation = std::min(report.min_separation, closest[k]);
  }
  return g;
}

}  // namespace rbcflow
