#include "tube_flow.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rbcflow {

double exterior_flux_factor(double chi) {
  if (!(chi > 0 && chi < std::numbers::pi / 4))
    throw std::invalid_argument("tube flow: the tube must fit in the box cross-section");
  const double c4 = chi * chi * chi * chi;
  const double c[5] = {0.077465, -0.109757, 0.122794, -0.146135, 0.244536};
  double series = -0.0509713 * c4, power = c4 * c4;
  for (int k = 0; k < 5; ++k, power *= c4) series += c[k] * power;
  return std::log(1.0 / chi) - 1.4763360 + 2.0 * chi - 0.5 * chi * chi + series;
}

double tube_effective_viscosity(double radius, double side, double mean_velocity,
                                double pressure_gradient, double mu) {
  const double G = -pressure_gradient;
  const double chi = std::numbers::pi * radius * radius / (side * side);
  const double q_external = G * std::pow(side, 4) / (4.0 * std::numbers::pi * mu) * exterior_flux_factor(chi);
  const double q_tube = side * side * mean_velocity - q_external;
  return std::numbers::pi * std::pow(radius, 4) * G / (8.0 * q_tube);
}

}  // namespace rbcflow
