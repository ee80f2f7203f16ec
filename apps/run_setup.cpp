#include "run_setup.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <stdexcept>

#include "case_vessel.h"
#include "geometry/cell_placement.h"
#include "geometry/wall_distance.h"
#include "io/case_derived.h"
#include "io/cell_layout.h"
#include "libsolver/membrane/membrane_law.h"

namespace rbcflow::cli {

namespace {

constexpr double kMinimumPlacementGap = 0.05;

Eigen::Vector3d to_eigen(const Vec3& v) { return {v[0], v[1], v[2]}; }

// The perturbation of section 9 added to a cell: amplitude Y_lm n, with Y_lm the real
// spherical harmonic of unit mean square on the sphere (m < 0: sin(|m| phi)) and n the
// outward normal of the cell.
void perturb(SHSurface& s, const CasePerturbation& p, const SHTransform& t) {
  SHCoeffs y(s.coeffs().order(), 1);
  if (p.m >= 0) {
    y.a(p.l, p.m) = 1.0;
  } else {
    y.b(p.l, -p.m) = 1.0;
  }
  Eigen::VectorXd Y = t.synthesize(y).col(0);
  double mean_square = 0;
  for (int q = 0; q < t.grid().size(); ++q) mean_square += t.grid().sphere_weight(q) * Y[q] * Y[q];
  Y /= std::sqrt(mean_square / (4 * std::numbers::pi));
  const SurfaceGeometry g = s.geometry(t);
  const Eigen::MatrixXd shift = (p.amplitude * Y).asDiagonal() * g.normal;
  s.coeffs().values() += t.analyze(shift, s.coeffs().order()).values();
}

std::function<Eigen::Vector3d(const Eigen::Vector3d&)> background(const BackgroundFlow& b) {
  const double rate = b.rate;
  switch (b.kind) {
    case FlowKind::shear: return [rate](const Eigen::Vector3d& x) { return Eigen::Vector3d(rate * x.z(), 0, 0); };
    case FlowKind::extensional:
      return [rate](const Eigen::Vector3d& x) { return Eigen::Vector3d(rate * x.x(), -rate * x.y(), 0); };
    case FlowKind::none: break;
  }
  return [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero().eval(); };
}

struct PlacedShapes {
  std::vector<SHSurface> rest, initial;  // the membranes' reference shapes and the starting shapes
  std::optional<std::string> note;       // how the cells were placed, where it is not plain
};

std::string fixed(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  return buf;
}

// Cells placed at random without overlap (a count, or the tube hematocrit of the meshed
// lumen), at least the collision threshold (and 0.05) apart and from the wall; in tubes
// narrower than the cell, stacked and pre-deformed (geometry/cell_placement.h).
PlacedShapes random_cells(const Case& c, const VesselMesh* vessel) {
  const CaseCells& k = *c.cells;
  if (c.domain.kind != DomainKind::periodic) {
    throw case_error(c, "cells.positions", "cells in a free domain must be listed (positions = [[x, y, z], ...])");
  }
  const SHSurface reference = reference_shape(k, k.order);
  int count = k.count.value_or(0);
  if (k.hematocrit) {
    if (!vessel) throw case_error(c, "cells.hematocrit", "a hematocrit needs a vessel");
    const double cell_volume = enclosed_volume(reference.geometry(SHTransform(k.order, SphGrid::gauss(k.order))));
    count = std::max(1, static_cast<int>(std::lround(*k.hematocrit * lumen_volume(*vessel) / cell_volume)));
  }
  PlacementSpec spec;
  spec.box = to_eigen(c.domain.box);
  spec.count = count;
  spec.gap = placement_gap(c);
  spec.seed = static_cast<std::uint64_t>(k.seed);
  spec.narrow_start = k.narrow_start == NarrowStartKind::parachute ? NarrowStart::parachute : NarrowStart::stretched;
  if (c.domain.mean_velocity) spec.flow = to_eigen(*c.domain.mean_velocity);
  if (c.domain.tube_velocity && c.vessel) spec.flow = *c.domain.tube_velocity * Eigen::Vector3d::Unit(c.vessel->axis);
  Placement p;
  try {
    p = place_cells(reference, spec, vessel);
  } catch (const std::runtime_error& e) {
    throw case_error(c, k.hematocrit ? "cells.hematocrit" : "cells.count", e.what());
  }
  PlacedShapes out{placed_surfaces(reference, p.cells), initial_surfaces(reference, p), std::nullopt};
  if (p.parachute) {
    out.note = "cells: the tube is narrower than a cell; placed stacked along the axis, folded face-on into "
               "parachutes (radius " + fixed(p.parachute_radius) + ", length " + fixed(p.parachute_length) +
               "; area and volume kept, the membranes' rest shape undeformed)";
  } else if (p.stretch_factors != Eigen::Vector3d::Ones()) {
    const Eigen::Vector3d& f = p.stretch_factors;
    out.note = "cells: the tube is narrower than a cell; placed stacked along the axis, pre-deformed (stretched " +
               fixed(f[0]) + " along the axis, " + fixed(f[1]) + " across, " + fixed(f[2]) +
               " through the thickness; volume kept, the membranes' rest shape undeformed)";
  }
  return out;
}

// The tube velocity is measured on the vessel's axis (the box centre in the cross-section)
// where it is straight: anywhere in a tube, half a period from a constriction's neck.
TubeDrive tube_drive(const Case& c) {
  const CaseVessel& v = *c.vessel;  // the parser allows tube_velocity with a tube or constriction only
  TubeDrive d;
  d.velocity = *c.domain.tube_velocity;
  d.axis = v.axis;
  d.axis_point = 0.5 * to_eigen(c.domain.box);
  const double length = c.domain.box[v.axis];
  d.axis_point[v.axis] = v.kind == VesselKind::constriction ? std::fmod(v.center + 0.5 * length, length) : 0.0;
  return d;
}

}  // namespace

double placement_gap(const Case& c) { return std::max(c.time.collision_threshold, kMinimumPlacementGap); }

RunSetup setup_run(const Case& c) {
  RunSetup r;
  CellStepperOptions& o = r.options;
  o.dt = time_step(c);
  r.steps = std::max(1L, static_cast<long>(std::ceil(c.time.end / o.dt - 1e-9)));
  o.scheme = c.time.scheme == TimeSchemeKind::ab2 ? TimeScheme::ab2 : TimeScheme::euler;
  o.viscosity_ratio = c.domain.viscosity_ratio;
  o.gmres_tolerance = c.solver.gmres_tolerance;
  o.gmres_max_iterations = c.solver.max_iterations;
  o.quadrature.radial_points = c.solver.patch_radial_points.value_or(0);
  o.volume_constraint = c.time.volume_constraint;
  o.wall_solve.tolerance = c.solver.gmres_tolerance;
  o.domain.ewald_tolerance = c.ewald.tolerance;
  // The solver chooses alpha, cutoff, grid and spline order for each of its sums from the
  // tolerance; a hand-set value would be silently ignored, so it is refused.
  for (const auto& [key, set] : {std::pair{"ewald.alpha", c.ewald.alpha.has_value()},
                                 std::pair{"ewald.cutoff", c.ewald.cutoff.has_value()},
                                 std::pair{"ewald.grid", c.ewald.grid.has_value()},
                                 std::pair{"ewald.spline_order", c.ewald.spline_order.has_value()}}) {
    if (set) {
      throw case_error(c, key, "rbcflow run does not take expert Ewald overrides yet; remove it (the solver "
                               "chooses every Ewald parameter from ewald.tolerance: see rbcflow check)");
    }
  }
  if (c.domain.kind == DomainKind::periodic) {
    o.domain.box = PeriodicBox(to_eigen(c.domain.box));
    if (c.domain.mean_velocity) o.mean_velocity = to_eigen(*c.domain.mean_velocity);
    if (c.domain.pressure_gradient) o.pressure_gradient = to_eigen(*c.domain.pressure_gradient);
    if (c.domain.tube_velocity) o.tube_drive = tube_drive(c);
  } else {
    o.background = background(c.domain.background_flow);
  }
  o.collision_threshold = c.time.collision_threshold;
  std::optional<VesselMesh> vessel;
  if (c.vessel) {
    vessel = build_vessel(c);
    r.wall = std::make_shared<const WallElements>(*vessel);
    o.wall = r.wall;
    if (c.vessel->kind == VesselKind::tube) r.tube_radius = 0.5 * c.vessel->diameter;
  }
  if (c.cells) {
    const CaseCells& k = *c.cells;
    r.grids = CellGrids::make(k.order, k.dealias * k.order);
    PlacedShapes placed;
    if (k.positions.empty()) {
      placed = random_cells(c, vessel ? &*vessel : nullptr);
      r.placement_note = placed.note;
    } else {
      check_cell_layout(c);
      placed.rest = placed_cells(k, k.order);
      placed.initial = placed.rest;
    }
    std::shared_ptr<const MembraneLaw> law = make_membrane_law(to_string(k.membrane.law), k.membrane.shear_modulus,
                                                               k.membrane.dilatation_modulus);
    for (std::size_t i = 0; i < placed.rest.size(); ++i) {
      SHSurface& s = placed.initial[i];
      Cell cell;
      cell.membrane =
          std::make_shared<const Membrane>(placed.rest[i], r.grids, MembraneParameters{law, k.membrane.bending_modulus});
      if (k.perturbation) perturb(s, *k.perturbation, *r.grids->n_grid);
      cell.shape = std::move(s);
      cell.body_force = to_eigen(k.body_force);
      r.cells.push_back(std::move(cell));
    }
  }
  return r;
}

}  // namespace rbcflow::cli
