#include "pries_law.h"

#include <cmath>
#include <stdexcept>

namespace rbcflow {

double pries_relative_viscosity(double D, double hd) {
  const double mu45 = 220.0 * std::exp(-1.3 * D) + 3.2 - 2.44 * std::exp(-0.06 * std::pow(D, 0.645));
  const double s = 1.0 / (1.0 + 1e-11 * std::pow(D, 12));
  const double C = (0.8 + std::exp(-0.075 * D)) * (-1.0 + s) + s;
  return 1.0 + (mu45 - 1.0) * (std::pow(1.0 - hd, C) - 1.0) / (std::pow(1.0 - 0.45, C) - 1.0);
}

double fahraeus_ratio(double D, double hd) {
  return hd + (1.0 - hd) * (1.0 + 1.7 * std::exp(-0.415 * D) - 0.6 * std::exp(-0.011 * D));
}

double discharge_hematocrit(double D, double ht) {
  if (!(ht > 0 && ht < 1)) throw std::invalid_argument("discharge_hematocrit: H_T must be in (0, 1)");
  // H_D fahraeus_ratio(D, H_D) increases with H_D on [0, 1] (from 0 to 1): bisection.
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (mid * fahraeus_ratio(D, mid) < ht ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double PhaseSeparationLaw::a() const {
  const double r = (alpha_um / beta_um) * (alpha_um / beta_um);
  return -13.29 * (r - 1) / (r + 1) * (1 - discharge_hematocrit) / parent_um;
}

double PhaseSeparationLaw::b() const { return 1 + 6.98 * (1 - discharge_hematocrit) / parent_um; }

double PhaseSeparationLaw::x0() const { return 0.964 * (1 - discharge_hematocrit) / parent_um; }

double PhaseSeparationLaw::cell_fraction(double blood_fraction) const {
  const double x = x0();
  if (blood_fraction <= x) return 0.0;
  if (blood_fraction >= 1 - x) return 1.0;
  const double y = (blood_fraction - x) / (1 - 2 * x);
  return 1 / (1 + std::exp(-(a() + b() * std::log(y / (1 - y)))));
}

}  // namespace rbcflow
