#pragma once
// The linear part of the periodic stresslet, eq. (3): T_ijk = -(8 pi / V) x_j delta_ik + T^per_ijk.
// Its double-layer term over closed surfaces, with the density psi = q (weights included) and
// r = x - x0 as in the rest of the module, is
//   -(8 pi / V) sum_S sum_{s in S} (q_s . n_s) (x_s - x0)_j
//     = -(8 pi / V) sum_S [ sum_{s in S} (q_s . n_s) (x_s - c_S)_j + Q_S (c_S - x0)_j ]
// with c_S a point of surface S (here the mean of its nodes) and Q_S = sum_{s in S} q_s . n_s
// its net flux. The first sum does not depend on where S lies among its periodic images; the
// second does, without bound: a cell carried through many periods (its shape is kept
// unwrapped) multiplies its flux by an ever longer lever arm to targets in the box. The exact
// flux of a surface velocity is zero (dV/dt = 0 for an incompressible interior) and a flux is
// not periodic anyway, so the second term is left out: the linear part is the same constant
// at every target, sum_S (8 pi/V) times minus the volume-weighted mean interior velocity of S
// (for q = u w: sum (u . n) (x - c) w = integral_V u dV when the flux vanishes).
// A uniform density on a closed surface has zero flux and gives -8 pi (V_S / V) delta_ij,
// cancelling the -V_S/V shift of the periodic part (docs/references.md section 1); without the
// linear part a translating cell's velocity depends wrongly on the viscosity ratio.
#include "libsolver/common/periodic_box.h"

namespace rbcflow {

// Sources stacked surface by surface, `points_per_surface` nodes each, every surface closed
// and continuous across the box faces (not folded back into the box). Returns the velocity
// term added at every target. Throws on mismatched row counts.
Eigen::RowVector3d double_layer_linear_part(const PeriodicBox& box, const PointField& sources, const PointField& q,
                                            const PointField& normals, int points_per_surface);

}  // namespace rbcflow
