#pragma once
// The empirical relative apparent viscosity of blood in glass tubes (Pries, Neuhaus &
// Gaehtgens, Am. J. Physiol. 263, 1992) and the Fahraeus effect (Pries et al. 1990), as given
// in docs/references.md section 7; the tube study (paper section 11.2, fig. 13) compares with it.
// D in micrometres; H_D the discharge and H_T the tube hematocrit.
namespace rbcflow {

// mu_rel(D, H_D) of the 1992 fit.
double pries_relative_viscosity(double diameter_um, double discharge_hematocrit);
// H_T / H_D = H_D + (1 - H_D)(1 + 1.7 exp(-0.415 D) - 0.6 exp(-0.011 D)).
double fahraeus_ratio(double diameter_um, double discharge_hematocrit);
// H_D for a tube hematocrit H_T (the inverse of H_T = H_D * fahraeus_ratio, by bisection).
double discharge_hematocrit(double diameter_um, double tube_hematocrit);

}  // namespace rbcflow
