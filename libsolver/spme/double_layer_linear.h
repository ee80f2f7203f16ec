#pragma once
// The linear part of the periodic stresslet, eq. (3): T_ijk = -(8 pi / V) x_j delta_ik + T^per_ijk.
// Its double-layer term, with the density psi = q (weights included) and r = x - x0 as in the
// rest of the module, is
//   -(8 pi / V) sum_s (q_s . n_s) (x_s - x0)_j
// at each target x0 (the x0 part vanishes for closed surfaces, where sum_s n_s w_s = 0, and
// makes the sum independent of the origin). For a uniform density on a closed surface it
// gives -8 pi (V_S / V) delta_ij, cancelling the -V_S/V shift of the periodic part
// (REFERENCES.md section 1); without it a translating cell's velocity depends wrongly on the
// viscosity ratio.
//
// The sum is not periodic: pass each closed surface unwrapped (continuous across the box
// faces), not folded back into the box.
#include "periodic_box.h"

namespace rbcflow {

// One row per target. O(sources + targets). Throws on mismatched row counts.
PointField double_layer_linear_part(const PeriodicBox& box, const PointField& sources,
                                    const PointField& q, const PointField& normals,
                                    const PointField& targets);

}  // namespace rbcflow
