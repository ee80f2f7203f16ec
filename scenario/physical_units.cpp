#include "scenario/physical_units.h"

namespace rbcflow {

std::optional<double> held_tube_velocity(const Case& c) {
  if (c.domain.tube_velocity) return c.domain.tube_velocity;
  if (c.domain.pseudo_shear_rate && c.vessel) return *c.domain.pseudo_shear_rate / c.units.rate_per_s * c.vessel->diameter;
  return std::nullopt;
}

}  // namespace rbcflow
