// The stepper's checkpoint items: one list of names for writing and reading (state_archive.h).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "cell_stepper.h"
#include "libsolver/parallel/ownership.h"
#include "libsolver/stepper/held_shapes.h"

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

// The order of coefficients of (rows x cols), cell k's; throws where they are none.
int order_of_coefficients(long long rows, long long cols, long k) {
  const int order = static_cast<int>(std::lround(std::sqrt(static_cast<double>(rows))));
  if (order < 1 || static_cast<long long>(order) * order != rows || cols != 3)
    throw std::invalid_argument("cell " + std::to_string(k) + " has no coefficients of an order");
  return order;
}

}  // namespace

void StepperState::archive(StateArchive& a, const Communicator* ranks) {
  const bool writing_part = !a.reading() && part;
  const bool reading_part = a.reading() && ranks && ranks->size() > 1;
  a.real("time", time);
  a.integer("steps", steps);
  long count = static_cast<long>(shapes.size());
  a.integer("cells/count", count);
  if (a.reading()) shapes.assign(count < 0 ? 0 : count, SHCoeffs());
  // U^{n-1}, U^{n-2}, U^{n-3}: in cell order, or in that of cells/velocity_order (written by
  // ranks from their parts).
  std::vector<int> velocity_order = writing_part ? part->order : std::vector<int>();
  if (writing_part && previous_velocity.cols() == 3) a.indices("cells/velocity_order", velocity_order);
  if (a.reading()) {
    a.indices("cells/velocity_order", velocity_order);
    if (!velocity_order.empty()) {
      std::vector<int> sorted = velocity_order;
      std::sort(sorted.begin(), sorted.end());
      for (std::size_t k = 0; k < sorted.size(); ++k)
        if (sorted.size() != static_cast<std::size_t>(count) || sorted[k] != static_cast<int>(k))
          throw std::invalid_argument("cells/velocity_order does not list every cell once");
    }
  }
  if (reading_part) {
    Part p;
    p.order = velocity_order;
    if (p.order.empty()) {
      p.order.resize(static_cast<std::size_t>(count));
      std::iota(p.order.begin(), p.order.end(), 0);
    }
    const OwnedRange block = owned_block(static_cast<int>(count), *ranks);
    p.begin = block.begin;
    p.end = block.end;
    part = std::move(p);
  }
  std::vector<char> mine;  // the cells whose items this part gives or reads
  if (writing_part || reading_part) {
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
    if (reading_part) {  // every rank learns every cell's order, reads its own cells' coefficients
      const auto [rows, cols] = a.matrix_size(name);
      const int order = order_of_coefficients(rows, cols, k);
      shapes[k] = shape_not_held(order);
      if (mine[static_cast<std::size_t>(k)]) shapes[k].values() = a.rows(name, 0, rows);
      continue;
    }
    Eigen::MatrixXd x = a.reading() ? Eigen::MatrixXd() : shapes[k].values();
    a.matrix(name, x, true);
    if (!a.reading()) continue;
    shapes[k] = SHCoeffs(order_of_coefficients(x.rows(), x.cols(), k), 3);
    shapes[k].values() = x;
  }
  column(a, "cells/initial_volume", volume0, count > 0);
  column(a, "cells/initial_area", area0, count > 0);
  const std::pair<const char*, Eigen::MatrixXd*> velocities[] = {{"cells/previous_velocity", &previous_velocity},
                                                                 {"cells/older_velocity", &older_velocity},
                                                                 {"cells/oldest_velocity", &oldest_velocity}};
  for (const auto& [name, u] : velocities) {
    if (writing_part) {
      if (u->cols() != 3) continue;
      const long long np = part->points_per_cell;
      a.part(name, count * np, part->begin * np, *u);
    } else if (reading_part) {  // this rank's block of the rows, in the order they were written
      const auto [rows, cols] = a.matrix_size(name);
      if (rows == 0) {
        u->resize(0, 0);  // absent
        continue;
      }
      if (count == 0 || rows % count != 0 || cols != 3)
        throw std::invalid_argument("a velocity does not fit the cells' order");
      const long long np = rows / count;
      part->points_per_cell = static_cast<int>(np);
      *u = a.rows(name, part->begin * np, (part->end - part->begin) * np);
    } else {
      a.matrix(name, *u, false);
      if (a.reading() && !velocity_order.empty()) to_cell_order(*u, velocity_order);
    }
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
  s.archive(a, &options_.domain.ranks);
  archive_wall(a);
  restore(s);
}

void CellStepper::load_rediscretised(StateArchive& a) {
  StepperState s;
  s.archive(a, &options_.domain.ranks);
  archive_wall(a);
  if (s.shapes.size() == cells_.size()) {
    for (std::size_t c = 0; c < cells_.size(); ++c) {
      const int order = cells_[c].shape.order();
      s.shapes[c] = shape_held(s.shapes[c]) ? s.shapes[c].resampled(order) : shape_not_held(order);
    }
  }
  for (Eigen::MatrixXd* u : {&s.previous_velocity, &s.older_velocity, &s.oldest_velocity}) u->resize(0, 0);
  if (s.part) s.part->points_per_cell = points_per_cell();
  restore(s);
}

}  // namespace rbcflow
