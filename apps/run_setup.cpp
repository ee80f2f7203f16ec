#include "run_setup.h"

#include <cmath>
#include <stdexcept>

#include "geometry/mesh_check.h"
#include "geometry/vessel.h"
#include "io/case_derived.h"
#include "io/cell_layout.h"
#include "libsolver/membrane/membrane_law.h"

namespace rbcflow::cli {

namespace {

Eigen::Vector3d to_eigen(const Vec3& v) { return {v[0], v[1], v[2]}; }

TubeSpec tube_spec(const Case& c) {
  TubeSpec t;
  t.diameter = c.vessel->diameter;
  t.axis = c.vessel->axis;
  t.box = to_eigen(c.domain.box);
  t.element_size = c.vessel->element_size;
  return t;
}

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

}  // namespace

VesselMesh build_vessel(const Case& c) {
  const CaseVessel& v = *c.vessel;
  try {
    switch (v.kind) {
      case VesselKind::tube: return tube(tube_spec(c));
      case VesselKind::constriction: {
        ConstrictionSpec s;
        s.tube = tube_spec(c);
        s.depth = v.depth;
        s.width = v.width;
        s.centre = v.center;
        return constriction(s);
      }
      case VesselKind::bifurcation: {
        BifurcationSpec s;
        s.tube = tube_spec(c);
        s.daughter_diameters = v.daughter_diameters;
        s.angle_deg = v.angle_deg;
        s.centre = v.center;
        return bifurcation(s);
      }
      case VesselKind::file: {
        VesselMesh wall = read_vessel(v.path.string());
        wall.surface.points *= v.scale;
        check_mesh(wall);
        return wall;
      }
    }
  } catch (const std::exception& e) {
    throw case_error(c, v.kind == VesselKind::file ? "vessel.path" : "vessel", e.what());
  }
  throw std::logic_error("build_vessel: unknown vessel kind");
}

RunSetup setup_run(const Case& c) {
  RunSetup r;
  CellStepperOptions& o = r.options;
  o.dt = time_step(c);
  r.steps = std::max(1L, static_cast<long>(std::ceil(c.time.end / o.dt - 1e-9)));
  o.scheme = c.time.scheme == TimeSchemeKind::ab2 ? TimeScheme::ab2 : TimeScheme::euler;
  o.viscosity_ratio = c.domain.viscosity_ratio;
  o.gmres_tolerance = c.solver.gmres_tolerance;
  o.gmres_max_iterations = c.solver.max_iterations;
  o.volume_constraint = c.time.volume_constraint;
  o.wall_solve.tolerance = c.solver.gmres_tolerance;
  o.domain.ewald_tolerance = c.ewald.tolerance;
  if (c.domain.kind == DomainKind::periodic) {
    o.domain.box = PeriodicBox(to_eigen(c.domain.box));
    if (c.domain.mean_velocity) o.mean_velocity = to_eigen(*c.domain.mean_velocity);
    if (c.domain.pressure_gradient) o.pressure_gradient = to_eigen(*c.domain.pressure_gradient);
  } else {
    o.background = background(c.domain.background_flow);
  }
  if (c.vessel) {
    r.wall = std::make_shared<const WallElements>(build_vessel(c));
    o.wall = r.wall;
    if (c.vessel->kind == VesselKind::tube) r.tube_radius = 0.5 * c.vessel->diameter;
  }
  if (c.cells) {
    const CaseCells& k = *c.cells;
    r.grids = CellGrids::make(k.order, k.dealias * k.order);
    if (k.positions.empty()) {
      throw case_error(c, "cells", "random placement (count or hematocrit without positions) is not available yet; "
                                   "list the cells' positions");
    }
    check_cell_layout(c);
    std::shared_ptr<const MembraneLaw> law = make_membrane_law(to_string(k.membrane.law), k.membrane.shear_modulus,
                                                               k.membrane.dilatation_modulus);
    for (SHSurface& s : placed_cells(k, k.order)) {
      Cell cell;
      cell.membrane = std::make_shared<const Membrane>(s, r.grids, MembraneParameters{law, k.membrane.bending_modulus});
      if (k.perturbation) perturb(s, *k.perturbation, *r.grids->n_grid);
      cell.shape = std::move(s);
      cell.body_force = to_eigen(k.body_force);
      r.cells.push_back(std::move(cell));
    }
  }
  return r;
}

}  // namespace rbcflow::cli
