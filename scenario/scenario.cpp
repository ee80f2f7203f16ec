#include "scenario/scenario.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

#include "geometry/contact/wall_distance.h"
#include "libsolver/membrane/membrane_law.h"
#include "libsolver/operators/cell_layers.h"
#include "libsolver/stepper/step_memory.h"
#include "scenario/cell_layout.h"
#include "scenario/derived.h"
#include "scenario/physical_units.h"
#include "scenario/vessel.h"

namespace rbcflow {

namespace {

Eigen::Vector3d to_eigen(const Vec3& v) { return {v[0], v[1], v[2]}; }

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

// The tube velocity is measured on the vessel's axis (the box centre in the cross-section)
// where it is straight: anywhere in a tube, half a period from a constriction's neck, in the
// middle of a bifurcation's parent (a quarter period before the split).
std::optional<TubeSection> tube_section(const Case& c) {
  if (!c.vessel || c.domain.kind != DomainKind::periodic) return std::nullopt;
  const CaseVessel& v = *c.vessel;
  if (v.kind != VesselKind::tube && v.kind != VesselKind::constriction && v.kind != VesselKind::bifurcation)
    return std::nullopt;
  TubeSection t;
  t.axis = v.axis;
  t.radius = 0.5 * v.diameter;
  t.axis_point = 0.5 * to_eigen(c.domain.box);
  const double length = c.domain.box[v.axis];
  if (v.kind == VesselKind::tube) t.axis_point[v.axis] = 0.0;
  if (v.kind == VesselKind::constriction) t.axis_point[v.axis] = std::fmod(v.center + 0.5 * length, length);
  if (v.kind == VesselKind::bifurcation) {
    t.axis_point[v.axis] = std::fmod(v.center + 0.75 * length, length);
    t.whole_period = false;
  }
  return t;
}

// The solver chooses alpha, cutoff, grid and spline order for each of its sums from the
// tolerance; a hand-set value would be silently ignored, so it is refused.
void refuse_ewald_overrides(const Case& c) {
  for (const auto& [key, set] : {std::pair{"ewald.alpha", c.ewald.alpha.has_value()},
                                 std::pair{"ewald.cutoff", c.ewald.cutoff.has_value()},
                                 std::pair{"ewald.grid", c.ewald.grid.has_value()},
                                 std::pair{"ewald.spline_order", c.ewald.spline_order.has_value()}}) {
    if (set) {
      throw case_error(c, key, "rbcflow does not take expert Ewald overrides yet; remove it (the solver "
                               "chooses every Ewald parameter from ewald.tolerance: see rbcflow check)");
    }
  }
}

CellStepperOptions solver_options(const Case& c) {
  CellStepperOptions o;
  o.dt = time_step(c);
  o.scheme = c.time.scheme == TimeSchemeKind::ab2 ? TimeScheme::ab2 : TimeScheme::euler;
  o.viscosity_ratio = c.domain.viscosity_ratio;
  o.gmres_tolerance = c.solver.gmres_tolerance;
  o.gmres_max_iterations = c.solver.max_iterations;
  o.quadrature.radial_points = c.solver.patch_radial_points.value_or(0);
  o.volume_constraint = c.time.volume_constraint;
  o.wall_solve.tolerance = c.solver.gmres_tolerance;
  o.wall_solve.preconditioner_block_nodes = c.solver.wall_preconditioner_block_nodes;
  o.domain.ewald_tolerance = c.ewald.tolerance;
  o.domain.ranks = Communicator::world();  // one rank unless started by mpirun
  if (c.domain.kind == DomainKind::periodic) {
    o.domain.box = PeriodicBox(to_eigen(c.domain.box));
    if (c.domain.mean_velocity) o.mean_velocity = to_eigen(*c.domain.mean_velocity);
    if (c.domain.pressure_gradient) o.pressure_gradient = to_eigen(*c.domain.pressure_gradient);
    o.tube = tube_section(c);
    o.tube_velocity = held_tube_velocity(c);
  } else {
    o.background = background(c.domain.background_flow);
  }
  o.collision_threshold = c.time.collision_threshold;
  o.contact = ContactLaw{c.time.contact_range, c.time.contact_strength};
  return o;
}

// The sums the solver will set up, each chosen from ewald.tolerance for its node count as
// libsolver's operators choose them; a tolerance too tight for the size is refused here.
std::vector<EwaldSum> ewald_sums(const Case& c, long cell_nodes, long wall_nodes, std::int64_t max_kept_pairs) try {
  std::vector<EwaldSum> sums;
  const PeriodicBox box(to_eigen(c.domain.box));
  const double tolerance = c.ewald.tolerance;
  auto add = [&](const char* what, EwaldKernel kernel, long nodes, const RealSpaceUse& real_space) {
    sums.push_back({what, nodes, choose_ewald_parameters(kernel, tolerance, box, nodes, nodes, real_space)});
  };
  if (cell_nodes > 0) {
    add("cells, single layer", EwaldKernel::stokeslet, cell_nodes, {});
    if (c.domain.viscosity_ratio != 1.0) {
      add("cells, double layer", EwaldKernel::stresslet, cell_nodes,
          double_layer_real_space(max_kept_pairs, tolerance, box, cell_nodes));
    }
  }
  if (wall_nodes > 0) add("wall, single layer", EwaldKernel::stokeslet, wall_nodes, {});
  return sums;
} catch (const std::invalid_argument& e) {
  // The chooser's limits on grid points and real-space pairs.
  throw case_error(c, "ewald.tolerance", e.what());
}

}  // namespace

Scenario prepare_scenario(const Case& c, std::optional<int> planned, std::optional<int> placed_at_order) {
  refuse_ewald_overrides(c);
  Scenario s;
  s.c = c;
  s.options = solver_options(c);
  const Communicator& ranks = s.options.domain.ranks;
  const RankLayout layout = planned ? RankLayout{*planned, *planned} : RankLayout{ranks.size(), ranks.ranks_on_this_machine()};
  s.steps = std::max(1L, static_cast<long>(std::ceil(c.time.end / s.options.dt - 1e-9)));
  if (c.vessel) {
    s.vessel = build_vessel(c);
    s.lumen_volume = lumen_volume(*s.vessel);
    if (c.vessel->kind == VesselKind::tube) s.tube_radius = 0.5 * c.vessel->diameter;
    s.branches = vessel_branches(c);
    // A tube's or constriction's flow is its meter's; other vessels' is measured per branch.
    s.branch_flow_by_meter = s.options.tube && s.options.tube->whole_period;
    if (!s.branch_flow_by_meter)
      for (const VesselBranch& b : s.branches) s.options.flux_sections.push_back(candidate_sections(b));
  }
  const long wall_nodes = s.vessel ? s.vessel->surface.num_points() : 0;
  if (!c.cells) {
    if (c.domain.kind == DomainKind::periodic) s.ewald = ewald_sums(c, 0, wall_nodes, 0);
    apply_memory_budget(s, layout);
    return s;
  }
  const CaseCells& k = *c.cells;
  s.grids = CellGrids::make(k.order, k.dealias * k.order);
  const int placement_order = placed_at_order.value_or(k.order);
  Case placed_case = c;
  placed_case.cells->order = placement_order;
  InitialCells placed = initial_cells(placed_case, s.vessel ? &*s.vessel : nullptr);
  for (std::vector<SHSurface>* shapes : {&placed.rest, &placed.initial}) {
    for (SHSurface& shape : *shapes) shape.coeffs() = shape.coeffs().resampled(k.order);
  }
  s.placement_note = placed.note;
  const std::shared_ptr<const MembraneLaw> law =
      make_membrane_law(to_string(k.membrane.law), k.membrane.shear_modulus, k.membrane.dilatation_modulus);
  // The rest shapes are rigid motions of one reference shape (cell_layout.h): one set of rest
  // metrics serves every membrane.
  SHSurface reference = reference_shape(k, placement_order);
  reference.coeffs() = reference.coeffs().resampled(k.order);
  const auto rest = std::make_shared<const RestMetrics>(reference, *s.grids);
  double cells_volume = 0;
  for (std::size_t i = 0; i < placed.rest.size(); ++i) {
    Cell cell;
    cell.membrane = std::make_shared<const Membrane>(placed.rest[i], s.grids,
                                                     MembraneParameters{law, k.membrane.bending_modulus}, rest);
    cell.shape = std::move(placed.initial[i]);
    cell.body_force = to_eigen(k.body_force);
    cells_volume += enclosed_volume(cell.shape.geometry(*s.grids->n_grid));
    s.cells.push_back(std::move(cell));
  }
  if (s.lumen_volume) s.tube_hematocrit = cells_volume / *s.lumen_volume;
  const long cell_nodes = static_cast<long>(s.cells.size()) * s.grids->n_grid->grid().size();
  if (c.domain.kind == DomainKind::periodic) {
    s.ewald = ewald_sums(c, cell_nodes, wall_nodes, s.options.domain.max_kept_pairs);
  }
  apply_memory_budget(s, layout);
  if (!s.keeps_pair_coefficients && c.domain.kind == DomainKind::periodic) {
    s.ewald = ewald_sums(c, cell_nodes, wall_nodes, s.options.domain.max_kept_pairs);  // the choice without them
    estimate_memory_without_kept_pairs(s, layout);
  }
  return s;
}

std::unique_ptr<CellStepper> make_stepper(Scenario& s) {
  // The set-up (the wall's operator, its LU, the Krylov seeds' solves) holds a fraction of what
  // a step holds, so its heaps keep what it frees for its next product even in a run that
  // returns freed memory: mapped afresh, each of the seeds' products faulted its arrays in again
  // (a tenth of the 1,000 cells' set-up). Such a run returns it from its first step on, whose
  // start gives back what the heaps hold free (CellStepper::solve, step_memory.h).
  reuse_freed_memory();
  if (s.vessel) s.options.wall = std::make_shared<const WallElements>(*s.vessel);
  auto stepper = std::make_unique<CellStepper>(std::move(s.cells), s.grids, s.options);
  if (!s.reuses_freed_memory) return_freed_memory();
  return stepper;
}

}  // namespace rbcflow
