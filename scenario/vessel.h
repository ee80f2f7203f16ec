#pragma once
// The vessel of a case, meshed: the one translation from the [vessel] keys to the geometry
// builders (scenario.h builds it for run and check; `rbcflow mesh` calls it alone).
#include <vector>

#include "geometry/vessel/vessel_branch.h"
#include "geometry/vessel/vessel_mesh.h"
#include "io/case.h"

namespace rbcflow {

// Throws CaseError (exit 2) when the case has no vessel or the builder rejects it (an
// infeasible layout, a bad mesh file), naming [vessel] or vessel.path.
VesselMesh build_vessel(const Case& c);

// The branches of the case's vessel (geometry/vessel/vessel_branches.h): one for a tube or a
// constriction, three for a bifurcation, one per segment of a network; none for a vessel from
// a file (its branches are not known) or without a vessel.
std::vector<VesselBranch> vessel_branches(const Case& c);

}  // namespace rbcflow
