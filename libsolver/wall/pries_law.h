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

// Phase separation at a diverging bifurcation (Pries et al., Am. J. Physiol. 289, H2657, 2005,
// the 1990 model refitted): the fraction of the parent's red cell flux that daughter alpha
// receives, for the fraction `blood_fraction` of the parent's blood flow it receives,
//   FQ_E = 1 / (1 + exp(-(A + B logit((FQ_B - X0) / (1 - 2 X0))))),  X0 < FQ_B < 1 - X0,
// 0 below X0 and 1 above 1 - X0, with logit(x) = ln(x / (1 - x)) and, D in um,
//   A = -13.29 ((D_alpha / D_beta)^2 - 1) / ((D_alpha / D_beta)^2 + 1) (1 - H_D) / D_F,
//   B = 1 + 6.98 (1 - H_D) / D_F,  X0 = 0.964 (1 - H_D) / D_F.
// X0 is the blood fraction below which a daughter gets no cells (the plasma skimmed from the
// parent's cell-free layer); B > 1 makes the split disproportionate (the daughter with more
// flow gets a larger share of the cells); A shifts it towards the wider daughter.
struct PhaseSeparationLaw {
  double parent_um = 0, alpha_um = 0, beta_um = 0;  // D_F, D_alpha, D_beta
  double discharge_hematocrit = 0;                  // the parent's H_D
  double a() const;
  double b() const;
  double x0() const;
  double cell_fraction(double blood_fraction) const;
};

}  // namespace rbcflow
