#pragma once
// Effective viscosity of the flow in a straight periodic tube along a box axis with a square
// cross-section L x L (eq. 45-46): the flux outside the tube (Sangani & Acrivos, Int. J.
// Multiphase Flow 8, 1982; the paper's constant 1.47644 is exactly 4 ln Gamma(1/4) - 2 ln(2 pi)
// = 1.4763360) is subtracted from the total flux L^2 <u>; mu_eff = pi a^4 G / (8 Q_tube),
// G = -<dp/dz>.
namespace rbcflow {

// Q_external / (G L^4 / (4 pi mu)) as a function of chi = pi a^2 / L^2 (eq. 45).
double exterior_flux_factor(double chi);

double tube_effective_viscosity(double radius, double side, double mean_velocity,
                                double pressure_gradient, double mu = 1.0);

}  // namespace rbcflow
