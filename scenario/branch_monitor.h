#pragma once
// branches.csv: after every step, each branch's flow rate, the cells in it and the cells that
// have crossed its mid-section (geometry/vessel/vessel_branch.h). The flow rate of a tube or a
// constriction is the tube meter's pi a^2 U (tube_drive.h: exact with cells up to its cell-free
// calibration); of a bifurcation's or network's branches, the flux through the branch's
// clearest section (section_flux.h). A cell is in the branch whose centreline is nearest its
// centroid; it has crossed a mid-section when its centroid went from behind the section's
// plane to in front of it (along the branch) within the section's radius; a crossing back
// counts -1.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "geometry/vessel/vessel_branch.h"
#include "io/csv.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow {

class BranchMonitor {
 public:
  // `tube_area`: pi a^2 where the flow is the tube meter's; `passed`: the counts to continue
  // from (a restart), zero when empty; `centroids`: the cells where the counting starts.
  BranchMonitor(std::vector<VesselBranch> branches, const Eigen::Vector3d& period, std::optional<double> tube_area,
                const std::vector<Eigen::Vector3d>& centroids, std::vector<long> passed = {});

  const std::vector<VesselBranch>& branches() const { return branches_; }
  // The rows after a step that ended with the cells' centroids at `centroids`.
  std::vector<BranchRow> update(long step, double time, const StepReport& r,
                                const std::vector<Eigen::Vector3d>& centroids);

 private:
  // Along branch b: the signed distance of x from the mid-section's plane and whether x is
  // within the section's radius of the branch's line.
  std::pair<double, bool> offset(int b, const Eigen::Vector3d& x) const;

  std::vector<VesselBranch> branches_;
  Eigen::Vector3d period_;
  std::optional<double> tube_area_;
  std::vector<long> passed_;
  std::vector<std::vector<double>> previous_;  // per branch, per cell: the offset after the last step
};

}  // namespace rbcflow
