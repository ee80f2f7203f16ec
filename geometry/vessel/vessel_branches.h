#pragma once
// The branches of each vessel kind (vessel_branch.h).
#include <vector>

#include "geometry/vessel/network.h"
#include "geometry/vessel/vessel.h"
#include "geometry/vessel/vessel_branch.h"

namespace rbcflow {

// The tube's axis across the box.
std::vector<VesselBranch> tube_branches(const TubeSpec& spec);
// The axis across the box, its middle half a box away from the neck at `centre`.
std::vector<VesselBranch> constriction_branches(const ConstrictionSpec& spec);
// The parent on the axis from the merge (half a box before the split, through the box face) to
// the split; each daughter parallel to the axis at its lateral offset (bifurcation_layout),
// split to merge, its mid-section in the middle of the loop where the daughters run parallel.
std::vector<VesselBranch> bifurcation_branches(const BifurcationSpec& spec);
// One branch per segment, as given.
std::vector<VesselBranch> network_branches(const NetworkSpec& spec);

}  // namespace rbcflow
