// The stepper's checkpoint items: one list of names for writing and reading (state_archive.h).
#include <cmath>
#include <stdexcept>
#include <string>

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

}  // namespace

void StepperState::archive(StateArchive& a) {
  a.real("time", time);
  a.integer("steps", steps);
  long count = static_cast<long>(shapes.size());
  a.integer("cells/count", count);
  if (a.reading()) shapes.assign(count < 0 ? 0 : count, SHCoeffs());
  for (long k = 0; k < count; ++k) {
    Eigen::MatrixXd x = a.reading() ? Eigen::MatrixXd() : shapes[k].values();
    a.matrix("cells/" + std::to_string(k) + "/coefficients", x, true);
    if (!a.reading()) continue;
    const int order = static_cast<int>(std::lround(std::sqrt(static_cast<double>(x.rows()))));
    if (order * order != x.rows() || x.cols() != 3)
      throw std::invalid_argument("cell " + std::to_string(k) + " has no coefficients of an order");
    shapes[k] = SHCoeffs(order, 3);
    shapes[k].values() = x;
  }
  column(a, "cells/initial_volume", volume0, count > 0);
  column(a, "cells/initial_area", area0, count > 0);
  a.matrix("cells/previous_velocity", previous_velocity, false);
  a.matrix("cells/older_velocity", older_velocity, false);
  a.matrix("cells/oldest_velocity", oldest_velocity, false);
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
  StepperState s = state();
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
