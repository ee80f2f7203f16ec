#include "scenario/branch_monitor.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

BranchMonitor::BranchMonitor(std::vector<VesselBranch> branches, const Eigen::Vector3d& period,
                             std::optional<double> tube_area, const std::vector<Eigen::Vector3d>& centroids,
                             std::vector<long> passed)
    : branches_(std::move(branches)), period_(period), tube_area_(tube_area), passed_(std::move(passed)) {
  if (passed_.empty()) passed_.assign(branches_.size(), 0);
  if (passed_.size() != branches_.size()) throw std::invalid_argument("BranchMonitor: one count per branch");
  for (int b = 0; b < static_cast<int>(branches_.size()); ++b) {
    previous_.emplace_back();
    for (const Eigen::Vector3d& x : centroids) previous_.back().push_back(offset(b, x).first);
  }
}

std::pair<double, bool> BranchMonitor::offset(int b, const Eigen::Vector3d& x) const {
  const VesselBranch& branch = branches_[b];
  const Eigen::Vector3d d = minimum_image(x - branch.centre(), period_), n = branch.direction();
  const double along = d.dot(n);
  return {along, (d - along * n).norm() <= branch.radius};
}

std::vector<BranchRow> BranchMonitor::update(long step, double time, const StepReport& r,
                                             const std::vector<Eigen::Vector3d>& centroids) {
  const int nb = static_cast<int>(branches_.size());
  std::vector<int> cells(nb, 0);
  for (const Eigen::Vector3d& x : centroids) ++cells[nearest_branch(branches_, x, period_)];
  std::vector<BranchRow> rows;
  for (int b = 0; b < nb; ++b) {
    for (int c = 0; c < static_cast<int>(centroids.size()); ++c) {
      const auto [now, within] = offset(b, centroids[c]);
      const double before = previous_[b][c];
      // A step moves a centroid far less than the radius; a jump is the minimum image turning
      // over half a box away.
      if (within && std::abs(now - before) < branches_[b].radius) {
        if (before <= 0 && now > 0) ++passed_[b];
        if (before > 0 && now <= 0) --passed_[b];
      }
      previous_[b][c] = now;
    }
    double flow = 0;
    if (tube_area_) {
      if (!r.tube_velocity) throw std::logic_error("BranchMonitor: the step reported no tube velocity");
      flow = *tube_area_ * *r.tube_velocity;
    } else {
      if (static_cast<int>(r.section_flux.size()) != nb)
        throw std::logic_error("BranchMonitor: the step reported no flux for each branch");
      flow = r.section_flux[b];
    }
    rows.push_back({step, time, b, flow, cells[b], passed_[b]});
  }
  return rows;
}

}  // namespace rbcflow
