#pragma once
// Parameters derived from a case alone, before its vessel is built: the reference cell, the
// time step (37), the flow axis. No solver needed; the Ewald parameters are
// the solver's to choose. What needs the meshed vessel (cell count, hematocrit) is in
// scenario.h.
#include <array>

#include "io/case.h"

namespace rbcflow {

// The reference cell: area A and volume V. For "rbc" A = 16.8, the paper's estimate used in
// (37); other shapes are measured on their spherical-harmonic surface of the case's order.
struct ReferenceCell {
  double area = 0;
  double volume = 0;
};
ReferenceCell reference_cell(const CaseCells& cells);

// h_eff = sqrt(A) / N and the explicit stability limit (37):
// dt < min(2.5 h^1.2 / E_D, 0.19 h^3.2 / E_B) (the E_B term is absent for E_B = 0; the
// neo-Hookean law, which has no E_D, uses its area-dilatation modulus K_S = 3 E_S in its place,
// as the validated capsule-shear tests do).
double effective_spacing(const CaseCells& cells);
double time_step_limit(const CaseCells& cells);
// The step a run takes: time.dt, or dt_safety times (37); with no cells and dt = "auto",
// time.end (a single step of the quasi-steady wall flow).
double time_step(const Case& c);

// The axis (0, 1, 2) the flow runs along: the vessel's; x for a free domain's background flow;
// otherwise the largest component of mean_velocity, pressure_gradient or the body force; z
// when all are zero. Renders look across it (side) and along it (end).
int flow_axis(const Case& c);
// The box side along flow_axis in a periodic domain, 0 in a free one: renders draw each cell
// wrapped into it (RenderOptions::period).
double flow_period(const Case& c);


}  // namespace rbcflow
