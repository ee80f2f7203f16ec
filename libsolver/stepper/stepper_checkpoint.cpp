// The stepper's checkpoint items: one list of names for writing and reading (state_archive.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "cell_stepper.h"

namespace rbcflow {
namespace {

// A vector of per-cell values as a column.
void column(StateArchive& a, const std::string& name, std::vector<double>& v, bool required) {
  Eigen::MatrixXd m = Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  a.matrix(name, m, required);
  if (a.reading()) v.assign(m.data(), m.data() + m.size());
}

void point_field(StateArchive& a, const std::string& name, PointField& f) {
  Eigen::MatrixXd m = f;
  a.matrix(name, m, false);
  if (!a.reading()) return;
  if (m.size() == 0) {
    f.resize(0, 3);  // absent: empty (a 0 x 0 matrix does not fit a field of 3 columns)
    return;
  }
  if (m.cols() != 3) throw std::invalid_argument(name + " is not a field of 3-vectors");
  f = m;
}

// Per-cell node data (np rows a cell) of a velocity order brought into cell order.
void to_cell_order(Eigen::MatrixXd& u, const std::vector<int>& order) {
  const long cells = static_cast<long>(order.size());
  if (u.size() == 0) return;
  if (cells == 0 || u.rows() % cells != 0) throw std::invalid_argument("a velocity does not fit the cells' order");
  CellOwners held_by{order, {0, static_cast<int>(cells)}};
  u = held_by.to_cell_order(u, static_cast<int>(u.rows() / cells));
}

}  // namespace

void StepperState::archive(StateArchive& a) {
  const bool writing_part = !a.reading() && part;
  a.real("time", time);
  a.integer("steps", steps);
  long count = static_cast<long>(shapes.size());
  a.integer("cells/count", count);
  if (a.reading()) shapes.assign(count < 0 ? 0 : count, SHCoeffs());
  std::vector<char> mine;  // the cells whose items this part gives
  if (writing_part) {
    mine.assign(static_cast<std::size_t>(count), 0);
    for (int p = part->begin; p < part->end; ++p) mine[static_cast<std::size_t>(part->order[p])] = 1;
  }
  for (long k = 0; k < count; ++k) {
    const std::string name = "cells/" + std::to_string(k) + "/coefficients";
    if (writing_part) {
      const int order = shapes[k].order();
      a.part(name, static_cast<long long>(order) * order, 0,
             mine[static_cast<std::size_t>(k)] ? shapes[k].values() : Eigen::MatrixXd(0, 3));
      continue;
    }
    Eigen::MatrixXd x = a.reading() ? Eigen::MatrixXd() : shapes[k].values();
    a.matrix(name, x, true);
    if (!a.reading()) continue;
    const int order = static_cast<int>(std::lround(std::sqrt(static_cast<double>(x.rows()))));
    if (order * order != x.rows() || x.cols() != 3)
      throw std::invalid_argument("cell " + std::to_string(k) + " has no coefficients of an order");
    shapes[k] = SHCoeffs(order, 3);
    shapes[k].values() = x;
  }
  column(a, "cells/initial_volume", volume0, count > 0);
  column(a, "cells/initial_area", area0, count > 0);
  // U^{n-1}, U^{n-2}, U^{n-3}: in cell order, or in that of cells/velocity_order (written by
  // ranks from their parts).
  const std::pair<const char*, Eigen::MatrixXd*> velocities[] = {{"cells/previous_velocity", &previous_velocity},
                                                                 {"cells/older_velocity", &older_velocity},
                                                                 {"cells/oldest_velocity", &oldest_velocity}};
  std::vector<int> velocity_order = writing_part ? part->order : std::vector<int>();
  if (writing_part && previous_velocity.cols() == 3) a.indices("cells/velocity_order", velocity_order);
  for (const auto& [name, u] : velocities) {
    if (!writing_part) {
      a.matrix(name, *u, false);
    } else if (u->cols() == 3) {
      const long long np = part->points_per_cell;
      a.part(name, count * np, part->begin * np, *u);
    }
  }
  if (a.reading()) {
    a.indices("cells/velocity_order", velocity_order);
    if (!velocity_order.empty()) {
      std::vector<int> sorted = velocity_order;
      std::sort(sorted.begin(), sorted.end());
      for (std::size_t k = 0; k < sorted.size(); ++k)
        if (sorted.size() != static_cast<std::size_t>(count) || sorted[k] != static_cast<int>(k))
          throw std::invalid_argument("cells/velocity_order does not list every cell once");
    }
    if (!velocity_order.empty())
      for (const auto& [name, u] : velocities) to_cell_order(*u, velocity_order);
  }
  point_field(a, "wall/previous_force", previous_wall_force);
  point_field(a, "wall/older_force", older_wall_force);
}

void CellStepper::archive_wall(StateArchive& a) const {
  if (!wall_) return;
  Eigen::MatrixXd points = wall_->elements().wall.surface.points;
  a.matrix("wall/points", points, true);
  if (a.reading() && points.rows() != wall_->elements().num_nodes())
    throw std::invalid_argument("its wall does not match the case's vessel as meshed now");
}

void CellStepper::save(StateArchive& a) const {
  StepperState s = a.takes_parts() ? held_state() : state();
  s.archive(a);
  archive_wall(a);
}

void CellStepper::load(StateArchive& a) {
  StepperState s;
  s.archive(a);
  archive_wall(a);
  restore(s);
}

void CellStepper::load_rediscretised(StateArchive& a) {
  StepperState s;
  s.archive(a);
  archive_wall(a);
  if (s.shapes.size() == cells_.size()) {
    for (std::size_t c = 0; c < cells_.size(); ++c) s.shapes[c] = s.shapes[c].resampled(cells_[c].shape.order());
  }
  for (Eigen::MatrixXd* u : {&s.previous_velocity, &s.older_velocity, &s.oldest_velocity}) u->resize(0, 0);
  restore(s);
}

}  // namespace rbcflow
