// rbcflow check: validate a case file and print what a user needs before a long run.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "cli.h"
#include "geometry/sph_transform.h"
#include "io/case.h"
#include "io/case_derived.h"
#include "io/cell_layout.h"
#include "io/output_dir.h"
#include "libsolver/operators/cell_layers.h"
#include "libsolver/spme/ewald_parameters.h"
#include "run_setup.h"

namespace rbcflow::cli {
namespace {

std::string vec(const Vec3& x) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%g, %g, %g]", x[0], x[1], x[2]);
  return buf;
}

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

void print_domain(const Case& c) {
  const CaseDomain& d = c.domain;
  if (d.kind == DomainKind::periodic) {
    std::printf("domain:  periodic box %g x %g x %g (volume %.4g)\n", d.box[0], d.box[1], d.box[2],
                d.box[0] * d.box[1] * d.box[2]);
    if (d.mean_velocity) std::printf("flow:    mean velocity <u> = %s\n", vec(*d.mean_velocity).c_str());
    if (d.pressure_gradient) {
      std::printf("flow:    mean pressure gradient <grad p> = %s\n", vec(*d.pressure_gradient).c_str());
    }
    if (d.tube_velocity) {
      std::printf("flow:    tube mean velocity %g along the vessel axis (<u> from a cell-free wall solve at "
                  "the start of the run)\n", *d.tube_velocity);
    }
  } else {
    std::printf("domain:  free (no Ewald sums)\n");
    std::printf("flow:    background %s", to_string(d.background_flow.kind).c_str());
    if (d.background_flow.kind != FlowKind::none) std::printf(", rate %g", d.background_flow.rate);
    std::printf("\n");
  }
  std::printf("         viscosity ratio lambda = %g\n", d.viscosity_ratio);
}

void print_vessel(const Case& c, const MemoryEstimate& memory) {
  if (!c.vessel) {
    std::printf("vessel:  none\n");
    return;
  }
  const CaseVessel& v = *c.vessel;
  std::printf("vessel:  %s along %s", to_string(v.kind).c_str(), axis_name(v.axis));
  if (v.kind == VesselKind::file) {
    std::printf(", %s (scale %g)", v.path.string().c_str(), v.scale);
  } else {
    std::printf(", D = %g", v.diameter);
  }
  if (v.kind == VesselKind::constriction) {
    std::printf(", neck d = %g at %g (depth %g, width %g)", v.diameter - v.depth, v.center, v.depth, v.width);
  }
  if (v.kind == VesselKind::bifurcation) {
    std::printf(", daughters %g and %g at %g deg from %g", v.daughter_diameters[0], v.daughter_diameters[1],
                v.angle_deg, v.center);
  }
  std::printf("\n         element size %g", v.element_size);
  if (memory.wall_nodes) std::printf(": about %d wall nodes", *memory.wall_nodes);
  if (const auto volume = vessel_volume(c)) std::printf("; volume %.4g", *volume);
  std::printf("\n");
}

// How run will place the cells. In a straight tube narrower than an undeformed cell's largest
// diameter plus the placement gap on both sides, no undeformed cell fits: run stacks them on
// the axis, pre-deformed as cells.narrow_start says (geometry/cell_placement.h).
void print_placement(const Case& c) {
  const CaseCells& k = *c.cells;
  if (!k.positions.empty()) {
    std::printf(", at the listed positions\n");
    return;
  }
  if (c.vessel && c.vessel->kind == VesselKind::tube) {
    const SHSurface reference = reference_shape(k, k.order);
    const double diameter = 2.0 * reference.geometry(SHTransform::gauss(k.order)).x.rowwise().norm().maxCoeff();
    const double fits = diameter + 2.0 * placement_gap(c);
    if (c.vessel->diameter < fits) {
      std::printf(",\n         stacked on the axis and pre-deformed (%s, seed %d): D = %g is below %.3f, the cell's "
                  "largest diameter plus twice the gap %g\n",
                  k.narrow_start == NarrowStartKind::parachute ? "folded face-on into parachutes" : "stretched edge-on",
                  k.seed, c.vessel->diameter, fits, placement_gap(c));
      return;
    }
  }
  std::printf(", placed at random (seed %d)\n", k.seed);
}

void print_cells(const Case& c, std::optional<int> count) {
  if (!c.cells) {
    std::printf("cells:   none\n");
    return;
  }
  const CaseCells& k = *c.cells;
  std::printf("cells:   ");
  if (count) {
    std::printf("%d %s", *count, to_string(k.shape).c_str());
  } else {
    std::printf("%s at hematocrit %g (the count is known once the vessel is meshed)", to_string(k.shape).c_str(),
                *k.hematocrit);
  }
  if (count) {
    if (const auto h = tube_hematocrit(c, *count)) std::printf(", tube hematocrit %.3f", *h);
  }
  if (k.hematocrit && count) std::printf(" (asked %g)", *k.hematocrit);
  print_placement(c);
  const int n = k.order, m = k.order * k.dealias;
  std::printf("         grid N = %d: %d x %d points, %d modes; de-aliasing M = %d: %d x %d points\n", n, n, 2 * n,
              n * n, m, m, 2 * m);
  std::printf("         membrane %s: Es %g, ", to_string(k.membrane.law).c_str(), k.membrane.shear_modulus);
  if (k.membrane.law != MembraneLawKind::neo_hookean) std::printf("Ed %g, ", k.membrane.dilatation_modulus);
  std::printf("Eb %g\n", k.membrane.bending_modulus);
  const ReferenceCell ref = reference_cell(k);
  std::printf("         reference cell: area %.4g, volume %.4g\n", ref.area, ref.volume);
}

void print_time(const Case& c) {
  const double dt = time_step(c);
  if (c.cells) {
    const double limit = time_step_limit(*c.cells);
    std::printf("time:    dt limit (37) %.4g (h_eff = sqrt(A)/N = %.4g)\n", limit, effective_spacing(*c.cells));
    if (c.time.dt && *c.time.dt > limit) {
      std::printf("         warning: dt = %g exceeds the limit (37); the run may be unstable\n", *c.time.dt);
    }
  }
  std::printf("         dt %.4g", dt);
  if (!c.time.dt) std::printf(" (auto: %g x limit)", c.time.dt_safety);
  std::printf(", %s, end %g: %.0f steps\n", to_string(c.time.scheme).c_str(), c.time.end,
              std::ceil(c.time.end / dt - 1e-9));
  std::printf("         collision threshold %g, volume constraint %s\n", c.time.collision_threshold,
              c.time.volume_constraint ? "on" : "off");
}

void print_output(const Case& c) {
  const CaseOutput& o = c.output;
  std::string formats = o.xdmf ? "xdmf" : "";
  if (o.vtk) formats.append(formats.empty() ? "vtk" : ", vtk");
  std::printf("output:  %s: frames every %d steps (%s)", o.dir.string().c_str(), o.every,
              formats.empty() ? "none" : formats.c_str());
  if (o.render) {
    std::printf(", renders (%s, %s, %dx%d) ", o.render_field.c_str(), to_string(o.render_view).c_str(),
                o.render_size[0], o.render_size[1]);
    if (o.render_every > 0) {
      std::printf("every %d steps", o.render_every);
    } else {
      std::printf("at the last step");
    }
  }
  if (o.checkpoint_every > 0) {
    std::printf(", checkpoints every %d steps\n", o.checkpoint_every);
  } else {
    std::printf(", no checkpoints\n");
  }
}

// One choice of the solver's Ewald chooser, indented under its heading; returns its grid's
// bytes in the memory model.
double print_choice(const std::string& what, EwaldKernel kernel, double tolerance, const PeriodicBox& box,
                    long nodes, const RealSpaceUse& real_space = {}) {
  std::printf("         %s (%ld nodes):\n", what.c_str(), nodes);
  const EwaldChoice choice = choose_ewald_parameters(kernel, tolerance, box, nodes, nodes, real_space);
  std::istringstream lines(to_string(choice));
  std::string line;
  std::getline(lines, line);  // the heading repeats the kernel and tolerance
  while (std::getline(lines, line)) std::printf("         %s\n", line.c_str());
  return ewald_grid_bytes(choice.parameters.grid);
}

// The parameters libsolver's chooser picks, for each Ewald sum of the run; their grids are
// added to the memory estimate (unless the grid is given).
void print_ewald(const Case& c, std::optional<int> count, MemoryEstimate& memory) try {
  double grids = 0;
  const CaseEwald& e = c.ewald;
  std::printf("ewald:   tolerance %g", e.tolerance);
  const PeriodicBox box(Eigen::Vector3d(c.domain.box[0], c.domain.box[1], c.domain.box[2]));
  if (c.cells && count && *count > 0) {
    const long nodes = 2L * c.cells->order * c.cells->order * *count;
    std::printf("\n");
    grids += print_choice("cells, single layer", EwaldKernel::stokeslet, e.tolerance, box, nodes);
    if (c.domain.viscosity_ratio != 1.0) {
      grids += print_choice("cells, double layer", EwaldKernel::stresslet, e.tolerance, box, nodes,
                            kDoubleLayerRealSpace);
    }
  } else if (c.cells) {
    std::printf(" (the cells' sums are chosen once the vessel is meshed and the count is known)\n");
  } else {
    std::printf("\n");
  }
  if (memory.wall_nodes) {
    grids += print_choice("wall, single layer", EwaldKernel::stokeslet, e.tolerance, box, *memory.wall_nodes);
  }
  if (!e.grid) memory.ewald = grids;
  if (e.alpha || e.cutoff || e.grid || e.spline_order) {
    std::printf("         expert overrides used instead:");
    if (e.alpha) std::printf(" alpha %g", *e.alpha);
    if (e.cutoff) std::printf(" cutoff %g", *e.cutoff);
    if (e.grid) std::printf(" grid %d x %d x %d", (*e.grid)[0], (*e.grid)[1], (*e.grid)[2]);
    if (e.spline_order) std::printf(" spline order %d", *e.spline_order);
    std::printf("\n");
  }
} catch (const std::invalid_argument& e) {
  // The chooser's limits on grid points and real-space pairs: a tolerance too tight for the size.
  throw case_error(c, "ewald.tolerance", e.what());
}

}  // namespace

int run_check(Args& args) {
  if (args.help_requested()) {
    std::printf(
        "usage: rbcflow check CASE.toml\n"
        "  Validates the case file (exit status 2 with file, line and key on an error) and\n"
        "  prints the derived parameters: cell count and hematocrit, grid sizes, the time step\n"
        "  limit (37), the Ewald parameters the solver will choose, the output, and a rough\n"
        "  memory estimate.\n");
    return 0;
  }
  const std::string file = args.positional("case file (CASE.toml)");
  args.finish();
  const Case c = read_case(file);
  check_cell_layout(c);
  check_output_dir(c, c.output.dir);

  const std::optional<int> count = cell_count(c);
  MemoryEstimate memory = memory_estimate(c, count.value_or(0));
  std::printf("case:    %s: \"%s\"\n", file.c_str(), c.title.c_str());
  print_domain(c);
  print_vessel(c, memory);
  print_cells(c, count);
  print_time(c);
  if (c.domain.kind == DomainKind::periodic) print_ewald(c, count, memory);
  std::printf("solver:  GMRES tolerance %g, at most %d iterations\n", c.solver.gmres_tolerance,
              c.solver.max_iterations);
  if (c.cells) {
    const int radial = c.solver.patch_radial_points.value_or(default_radial_points(c.cells->order));
    std::printf("         singular patches: %d radial x %d angular points (%s)\n", radial, 2 * radial,
                c.solver.patch_radial_points ? "set" : "default, max(8, ceil(3 sqrt(N)))");
  }
  print_output(c);
  std::printf("memory:  about %.0f MB (rough model: cells %.0f MB", memory.total() / 1e6, memory.cells / 1e6);
  if (memory.wall_nodes) {
    std::printf(", wall %.0f MB", memory.wall / 1e6);
  } else if (c.vessel) {
    std::printf(", wall not included until meshed");
  }
  if (memory.ewald > 0) std::printf(", Ewald grids %.0f MB", memory.ewald / 1e6);
  std::printf(")\ncase OK\n");
  return 0;
}

}  // namespace rbcflow::cli
