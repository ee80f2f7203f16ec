#pragma once
// The cells' shapes on several ranks (docs/scaling.md): between steps each rank holds only the
// shapes of its own cells, those it moved last (CellStepper's history owners). A step brings it
// the shapes it reads besides (its halo's, a cell whose owner changed) from the ranks that hold
// them, and an output step every shape, until the cells move. A shape not held keeps its order
// and no coefficients. One process holds every shape.
#include <vector>

#include "geometry/sph/sph_coeffs.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/communicator.h"

namespace rbcflow {

inline bool shape_held(const SHCoeffs& x) { return x.values().size() > 0; }
// Frees a shape's coefficients, keeping its order.
void release_shape(SHCoeffs& x);
// A shape of `order` not held.
SHCoeffs shape_not_held(int order);
// A shape's coefficients of its order allocated (NaN) where not held, to be filled.
void allocate_shape(SHCoeffs& x);

// The shapes of `cells` (cell numbers) that `held_by` gives other ranks, brought from them into
// `shapes` (indexed by cell number; allocated where not held). The cells `held_by` gives this
// rank are left as they are: their shapes must be held. Collective; returns how many came.
int bring_shapes(const std::vector<SHCoeffs*>& shapes, const CellOwners& held_by, const std::vector<int>& cells,
                 const Communicator& ranks);

// Every shape on every rank, from those of the ranks' own cells in `held_by` (whose blocks
// have owned_block's sizes, as cell_owners makes them). Collective.
void share_shapes(const std::vector<SHCoeffs*>& shapes, const CellOwners& held_by, const Communicator& ranks);

}  // namespace rbcflow
