#include "libsolver/stepper/collision.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>

#include "libsolver/parallel/ownership.h"
#include "libsolver/parallel/share_blocks.h"
#include "libsolver/stepper/cell_proximity.h"
#include "libsolver/stepper/held_shapes.h"

namespace rbcflow {
namespace {

// Points are pushed to h_s (1 + kOvershoot): the smoothed push then ends at or above h_s.
constexpr double kOvershoot = 0.01;
// The pushes are met to 1% of the largest at the pushed points (fit_push), within at most 50
// iterations (the slowest pushes, a single point at the first Gauss colatitude, keep ~0.15 of
// their size per analysis: 0.85^28 < 1%).
constexpr double kFitTolerance = 0.01;
constexpr int kFitIterations = 50;

struct Pass {
  std::vector<Eigen::MatrixXd> push;  // displacement of each grid point of the rank's block's cells
  std::vector<char> moved;
  int cell_pairs = 0, wall_contacts = 0;
  double min_separation = std::numeric_limits<double>::infinity();
  int closest_cell = -1, closest_other = -1;  // where min_separation was found (-1 other: the wall)
};

// A grid point of a cell closer than h_s to a neighbour: the separation it lacks (to h_s (1 +
// kOvershoot)) and the neighbour's outward normal at its projection.
struct Contact {
  int point = 0;
  double missing = 0;
  Eigen::Vector3d normal;
};

// The points of cell `a` within h_s of cell `b` translated by `offset` (a periodic image), in
// b's outward normal at the projection (section 11.2).
std::vector<Contact> contacts_with_cell(const CellView& a, const CellView& b, const SHCoeffs& b_coeffs,
                                        const Eigen::Vector3d& offset, const SphGrid& grid, double h_s,
                                        double& min_separation) {
  std::vector<Contact> contacts;
  const double target = h_s * (1.0 + kOvershoot);
  for (int p = 0; p < a.points.rows(); ++p) {
    const Eigen::Vector3d q = a.points.row(p).transpose() - offset;  // in b's own frame
    const std::optional<SurfaceProjection> s = project_within(b, b_coeffs, grid, q, 2.0 * h_s);
    if (!s) continue;
    min_separation = std::min(min_separation, s->signed_distance);
    if (s->signed_distance < h_s) contacts.push_back({p, target - s->signed_distance, s->normal});
  }
  return contacts;
}

// The cells near those of `mine` that another rank pushes, ascending: the shapes this rank reads.
std::vector<int> others_near(const Neighbourhood& h, const OwnedRange& mine) {
  std::vector<int> others;
  for (int a = mine.begin; a < mine.end; ++a)
    for (const Neighbour& nb : h.near[a])
      if (!mine.contains(nb.b)) others.push_back(nb.b);
  std::sort(others.begin(), others.end());
  others.erase(std::unique(others.begin(), others.end()), others.end());
  return others;
}

// The pushes of the cells `mine` (pass.push[a - mine.begin]; pass.moved of the others stays
// zero; owner[c]: cell c's rank), which read only the shapes of the cells near them; the
// pairs, contacts and smallest separation are the ranks' together.
Pass detect(const std::vector<SHSurface>& cells, std::vector<CellView>& views, const Neighbourhood& neighbourhood,
            const SHTransform& t, const WallDistance* wall, double h_s, const OwnedRange& mine,
            const std::vector<int>& owner, const Communicator& ranks) {
  const int n = static_cast<int>(cells.size());
  Pass pass;
  pass.push.assign(static_cast<std::size_t>(mine.size()), Eigen::MatrixXd::Zero(t.grid().size(), 3));
  pass.moved.assign(n, 0);
  const std::vector<std::vector<Neighbour>>& near = neighbourhood.near;
  const int pairs = neighbourhood.pairs;
  // The trees of the cells near this rank's.
  std::vector<char> tree_needed(n, 0);
  for (int a = mine.begin; a < mine.end; ++a)
    for (const Neighbour& nb : near[a]) tree_needed[nb.b] = 1;
  for (int a = 0; a < n; ++a)
    if (tree_needed[a]) build_tree(views[a], cells[a].coeffs(), t);
  // contacts[a][k]: cell a's points too close to its k-th neighbour; written by a's thread only.
  std::vector<std::vector<std::vector<Contact>>> contacts(n);
  for (int a = 0; a < n; ++a) contacts[a].resize(near[a].size());
  std::vector<char> wall_hit(n, 0);
  const double target = h_s * (1.0 + kOvershoot);
  // Each cell's smallest separation and what it is from (a cell, or -1: the wall).
  std::vector<double> cell_min(n, std::numeric_limits<double>::infinity());
  std::vector<int> cell_min_other(n, -1);
#pragma omp parallel for schedule(dynamic)
  for (int a = mine.begin; a < mine.end; ++a) {
    for (std::size_t k = 0; k < near[a].size(); ++k) {
      const Neighbour& nb = near[a][k];
      double separation = std::numeric_limits<double>::infinity();
      contacts[a][k] = contacts_with_cell(views[a], views[nb.b], cells[nb.b].coeffs(), nb.offset, t.grid(), h_s,
                                          separation);
      if (separation < cell_min[a]) {
        cell_min[a] = separation;
        cell_min_other[a] = nb.b;
      }
    }
    // The wall does not move: a point within h_s of it takes the whole push, along the wall
    // normal into the lumen.
    if (!wall || wall->closest(views[a].centre).signed_distance >= views[a].radius + 2.0 * h_s) continue;
    for (int p = 0; p < views[a].points.rows(); ++p) {
      const WallDistance::Query w = wall->closest(views[a].points.row(p).transpose());
      if (w.signed_distance < cell_min[a]) {
        cell_min[a] = w.signed_distance;
        cell_min_other[a] = -1;
      }
      if (w.signed_distance < h_s) {
        pass.push[a - mine.begin].row(p) += (target - w.signed_distance) * w.normal.transpose();
        wall_hit[a] = 1;
        pass.moved[a] = 1;
      }
    }
  }
  // A pair shares each push by the largest separation each side lacks: a side that finds
  // deficit D_a takes D_a / (D_a + D_b) of its points' missing separation, half each when the
  // two see the same (two smooth surfaces), all of it when the other side's grid points find
  // none (a tip against a flat face, between the face's grid points). The shares sum to one,
  // so the pair ends h_s apart, not 2 h_s - d.
  // Each side's deficit is found by its cell's rank and sent to the rank of the other side's
  // cell where that is another (the entries each rank sends another follow from the shared
  // neighbourhood, in the same order on both): only the pairs that cross the ranks travel.
  std::vector<double> deficit(2 * static_cast<std::size_t>(pairs), 0.0);  // per pair: first side, second side
  std::vector<int> sides(pairs, 0), first_side_cell(pairs, 0);
  std::vector<std::vector<int>> side_of(n);
  for (int a = 0; a < n; ++a) {
    for (std::size_t k = 0; k < near[a].size(); ++k) {
      const int pair = near[a][k].pair;
      const int side = sides[pair]++;
      side_of[a].push_back(side);
      if (side == 0) first_side_cell[pair] = a;
      if (!mine.contains(a)) continue;
      for (const Contact& c : contacts[a][k]) deficit[2 * pair + side] = std::max(deficit[2 * pair + side], c.missing);
    }
  }
  if (ranks.size() > 1) {
    // The (pair, side) entries cell a's rank sends cell b's for each neighbour of a on another
    // rank, in the order of a and its neighbours: calls f(entry, a's rank, b's rank).
    const auto crossing = [&](auto&& f) {
      for (int a = 0; a < n; ++a)
        for (std::size_t k = 0; k < near[a].size(); ++k)
          if (owner[a] != owner[near[a][k].b]) f(2 * near[a][k].pair + side_of[a][k], owner[a], owner[near[a][k].b]);
    };
    const std::size_t p = static_cast<std::size_t>(ranks.size());
    std::vector<std::vector<double>> out(p);
    std::vector<int> out_counts(p, 0), in_counts(p, 0);
    std::vector<int> arriving;  // entries in the order they come, rank after rank
    std::vector<std::vector<int>> arriving_from(p);
    crossing([&](int entry, int from, int to) {
      if (from == ranks.rank()) out[static_cast<std::size_t>(to)].push_back(deficit[entry]);
      if (to == ranks.rank()) arriving_from[static_cast<std::size_t>(from)].push_back(entry);
    });
    std::vector<double> sent;
    for (std::size_t r = 0; r < p; ++r) {
      sent.insert(sent.end(), out[r].begin(), out[r].end());
      out_counts[r] = static_cast<int>(out[r].size());
      arriving.insert(arriving.end(), arriving_from[r].begin(), arriving_from[r].end());
      in_counts[r] = static_cast<int>(arriving_from[r].size());
    }
    std::vector<double> received(arriving.size());
    ranks.exchange(sent, out_counts, received, in_counts);
    for (std::size_t i = 0; i < arriving.size(); ++i) deficit[static_cast<std::size_t>(arriving[i])] = received[i];
  }
  for (int a = mine.begin; a < mine.end; ++a) {
    for (std::size_t k = 0; k < near[a].size(); ++k) {
      if (contacts[a][k].empty()) continue;
      const int pair = near[a][k].pair;
      const double own = deficit[2 * pair + side_of[a][k]], other = deficit[2 * pair + 1 - side_of[a][k]];
      const double share = own / (own + other);
      for (const Contact& c : contacts[a][k])
        pass.push[a - mine.begin].row(c.point) += share * c.missing * c.normal.transpose();
      pass.moved[a] = 1;
    }
  }
  // A pair is hit when either side lacks separation (a deficit is positive exactly where its
  // side has contacts); the rank of its first side's cell counts it.
  long pairs_hit = 0;
  for (int pair = 0; pair < pairs; ++pair)
    if (mine.contains(first_side_cell[pair]) && (deficit[2 * pair] > 0 || deficit[2 * pair + 1] > 0)) ++pairs_hit;
  for (int a = mine.begin; a < mine.end; ++a) {
    if (cell_min[a] < pass.min_separation) {
      pass.min_separation = cell_min[a];
      pass.closest_cell = a;
      pass.closest_other = cell_min_other[a];
    }
  }
  // The ranks' smallest separation, at the first cell that has it (as one rank finds it).
  const double smallest = ranks.min(pass.min_separation);
  const int closest = static_cast<int>(ranks.min(pass.min_separation == smallest ? pass.closest_cell : n));
  pass.closest_other = static_cast<int>(ranks.min(pass.closest_cell == closest ? pass.closest_other : n));
  pass.closest_cell = closest;
  pass.min_separation = smallest;
  pass.cell_pairs = static_cast<int>(ranks.sum(pairs_hit));
  pass.wall_contacts = static_cast<int>(ranks.sum(static_cast<long>(std::count(wall_hit.begin(), wall_hit.end(), 1))));
  return pass;
}

// The order-N displacement that moves every pushed grid point by its push (section 11.2
// moves each such point until it is h_s away) and carries the others with the expansion. The
// analysis of the push field alone (zero at the points not pushed) is its L2 projection, which
// keeps only part of a local push: w_p N^2 / 4 pi ~ (pi / 4) sin(theta) of a single grid
// point's, less near the poles. Richardson iterations on the pushed points, d += A M (P - S d)
// (A analysis, S synthesis, M the pushed points), converge to the displacement that meets the
// pushes there: M S A M is a product of two projections orthogonal in the quadrature inner
// product, so its eigenvalues lie in [0, 1] and the iteration never amplifies the residual.
// A single pushed point's displacement is the band-limited kernel centred on it, largest there.
SHCoeffs fit_push(const SHTransform& t, const Eigen::MatrixXd& push, int order) {
  const Eigen::VectorXd size = push.rowwise().norm();
  const double tolerance = kFitTolerance * size.maxCoeff();
  SHCoeffs d = t.analyze(push, order);
  Eigen::MatrixXd residual(push.rows(), 3);
  for (int it = 0; it < kFitIterations; ++it) {
    residual = push - t.synthesize(d);
    double largest = 0;
    for (int p = 0; p < push.rows(); ++p) {
      if (size[p] == 0) {
        residual.row(p).setZero();
      } else {
        largest = std::max(largest, residual.row(p).norm());
      }
    }
    if (largest <= tolerance) break;
    d.values() += t.analyze(residual, order).values();
  }
  return d;
}

}  // namespace

CollisionReport remove_collisions(std::vector<SHSurface>& cells, const SHTransform& grid_transform,
                                  const Eigen::Vector3d& period, const WallDistance* wall, double threshold,
                                  const Communicator& ranks, int max_iterations) {
  if (!(threshold > 0)) throw std::invalid_argument("remove_collisions: the threshold h_s must be positive");
  if (!grid_transform.grid().is_gauss())
    throw std::invalid_argument("remove_collisions: the grid transform needs a Gauss grid");
  for (const SHSurface& c : cells)
    if (c.order() > grid_transform.order())
      throw std::invalid_argument("remove_collisions: a cell's order exceeds that of the grid transform");

  const int n = static_cast<int>(cells.size());
  const OwnedRange mine = owned_block(n, ranks);
  std::vector<int> owner(n);
  for (int r = 0; r < ranks.size(); ++r) {
    const OwnedRange b = owned_block(n, r, ranks.size());
    std::fill(owner.begin() + b.begin, owner.begin() + b.end, r);
  }
  std::vector<std::vector<std::span<double>>> shapes(n);  // each cell's coefficients
  for (int i = 0; i < n; ++i)
    shapes[i] = {std::span<double>(cells[i].coeffs().values().data(), cells[i].coeffs().values().size())};
  CollisionReport report;
  std::vector<SHCoeffs> before(n);
  for (int pass_index = 0;; ++pass_index) {
    // Each rank its own cells' points, bounding spheres shared (4 numbers a cell), and the
    // shapes of the others' cells near its own brought from their ranks.
    std::vector<CellView> views(n);
    std::vector<std::vector<std::span<double>>> spheres(n);
    for (int i = 0; i < n; ++i) spheres[i] = {std::span<double>(views[i].centre.data(), 3), std::span<double>(&views[i].radius, 1)};
    for (int i = mine.begin; i < mine.end; ++i) views[i] = cell_view(cells[i].coeffs(), grid_transform);
    share_blocks(ranks, spheres);
    const Neighbourhood near = find_neighbours(views, period, threshold);
    const std::vector<int> others = others_near(near, mine);
    for (const int i : others) {  // a shape not held here (held_shapes.h) is allocated to be filled
      if (shape_held(cells[i].coeffs())) continue;
      allocate_shape(cells[i].coeffs());
      shapes[i] = {std::span<double>(cells[i].coeffs().values().data(), cells[i].coeffs().values().size())};
    }
    report.shapes_brought += bring_items(ranks, owner, others, shapes);
    const Pass pass = detect(cells, views, near, grid_transform, wall, threshold, mine, owner, ranks);
    if (pass_index == 0) {
      report.cell_pairs = pass.cell_pairs;
      report.wall_contacts = pass.wall_contacts;
      report.max_overlap = std::max(0.0, threshold - pass.min_separation);
    }
    report.min_separation = pass.min_separation;
    report.closest_cell = pass.closest_cell;
    report.closest_other = pass.closest_other;
    const long moved = ranks.sum(static_cast<long>(std::count(pass.moved.begin(), pass.moved.end(), 1)));
    if (moved == 0) break;
    if (pass_index == max_iterations) {
      report.converged = false;
      break;
    }
    for (int i = mine.begin; i < mine.end; ++i) {
      if (!pass.moved[i]) continue;
      if (before[i].order() == 0) before[i] = cells[i].coeffs();
      cells[i].coeffs().values() += fit_push(grid_transform, pass.push[i - mine.begin], cells[i].order()).values();
    }
    ++report.passes;
  }
  for (int i = mine.begin; i < mine.end; ++i) {
    if (before[i].order() == 0) continue;
    SHCoeffs change = cells[i].coeffs();
    change.values() -= before[i].values();
    report.max_displacement =
        std::max(report.max_displacement, grid_transform.synthesize(change).rowwise().norm().maxCoeff());
  }
  report.max_displacement = -ranks.min(-report.max_displacement);
  return report;
}

}  // namespace rbcflow
