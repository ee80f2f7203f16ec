#pragma once
// Non-dimensional values in the physical units a physiologist reads, from the scales of section 6
// ([units] of a case): lengths in a* (um), time in 1 / k*, velocity in a* k*, stress in mu* k*,
// viscosity in mu*. The paper's defaults: a* = 2.82 um, k* = 100 1/s, mu* = 1.2 mPa s, so that
// the velocity scale is 282 um/s and the stress scale 0.12 Pa.
#include "io/case.h"

namespace rbcflow {

struct PhysicalUnits {
  explicit PhysicalUnits(const CaseUnits& u) : u_(u) {}

  double micrometres(double length) const { return length * u_.length_um; }
  double milliseconds(double time) const { return time * 1e3 / u_.rate_per_s; }
  double mm_per_s(double velocity) const { return velocity * u_.length_um * u_.rate_per_s * 1e-3; }
  double per_second(double rate) const { return rate * u_.rate_per_s; }
  double pascals(double stress) const { return stress * u_.plasma_viscosity_mpas * 1e-3 * u_.rate_per_s; }
  double pa_per_um(double pressure_gradient) const { return pascals(pressure_gradient) / u_.length_um; }
  // 1 mmHg = 133.322 Pa; 1 Pa/um = 1000 Pa/mm.
  double mmhg_per_mm(double pressure_gradient) const { return pa_per_um(pressure_gradient) * 1e3 / 133.322; }
  double mpa_s(double viscosity) const { return viscosity * u_.plasma_viscosity_mpas; }
  // A membrane modulus (force per length: stress x length), N/m.
  double newtons_per_m(double modulus) const { return pascals(modulus) * u_.length_um * 1e-6; }
  // A bending modulus (force x length), N m.
  double newton_metres(double modulus) const { return newtons_per_m(modulus) * u_.length_um * u_.length_um * 1e-12; }

 private:
  CaseUnits u_;
};

// The tube velocity a case holds (domain.tube_velocity, or domain.pseudo_shear_rate x D / k*,
// D the tube's diameter away from any neck); none when it drives otherwise.
std::optional<double> held_tube_velocity(const Case& c);

}  // namespace rbcflow
