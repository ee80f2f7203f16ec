// rbcflow check: validate a case file exactly as `rbcflow run` does before its first step (the
// scenario is prepared: vessel meshed, cells placed and checked) and print what a user needs
// before a long run.
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"
#include "geometry/sph/sph_transform.h"
#include "io/case.h"
#include "io/output_dir.h"
#include "libsolver/operators/cell_layers.h"
#include "scenario/derived.h"
#include "scenario/physical_units.h"
#include "scenario/scenario.h"

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
    if (const std::optional<double> U = held_tube_velocity(c)) {
      const PhysicalUnits si(c.units);
      const double D = c.vessel->diameter, rate = *U / D;
      std::printf("flow:    tube mean velocity U = %.4g (%.3g mm/s), pseudo-shear rate U/D = %.4g (%.3g 1/s), held "
                  "every step by <u>\n", *U, si.mm_per_s(*U), rate, si.per_second(rate));
      // Poiseuille without cells: wall shear stress 8 mu U / D, pressure gradient 32 mu U / D^2.
      std::printf("         without cells: wall shear stress %.4g (%.3g Pa), pressure gradient %.4g (%.3g Pa/um, "
                  "%.3g mmHg/mm)\n", 8 * rate, si.pascals(8 * rate), 32 * rate / D, si.pa_per_um(32 * rate / D),
                  si.mmhg_per_mm(32 * rate / D));
    }
  } else {
    std::printf("domain:  free (no Ewald sums)\n");
    std::printf("flow:    background %s", to_string(d.background_flow.kind).c_str());
    if (d.background_flow.kind != FlowKind::none) std::printf(", rate %g", d.background_flow.rate);
    std::printf("\n");
  }
  std::printf("         viscosity ratio lambda = %g\n", d.viscosity_ratio);
}

void print_units(const Case& c) {
  const PhysicalUnits si(c.units);
  std::printf("units:   a = %g um, 1/k* = %.4g ms, plasma %g mPa s: velocity %.4g mm/s, stress %.4g Pa, "
              "pressure gradient %.4g Pa/um ([units])\n",
              c.units.length_um, si.milliseconds(1), c.units.plasma_viscosity_mpas, si.mm_per_s(1), si.pascals(1),
              si.pa_per_um(1));
}

void print_vessel(const Scenario& s) {
  const Case& c = s.c;
  if (!c.vessel) {
    std::printf("vessel:  none\n");
    return;
  }
  const CaseVessel& v = *c.vessel;
  std::printf("vessel:  %s along %s", to_string(v.kind).c_str(), axis_name(v.axis));
  if (v.kind == VesselKind::file) {
    std::printf(", %s (scale %g)", v.path.string().c_str(), v.scale);
  } else if (v.kind == VesselKind::network) {
    std::printf(", %zu segments", v.segments.size());
  } else {
    std::printf(", D = %g (%.3g um)", v.diameter, PhysicalUnits(c.units).micrometres(v.diameter));
  }
  if (v.kind == VesselKind::constriction) {
    std::printf(", neck d = %g at %g (depth %g, width %g)", v.diameter - v.depth, v.center, v.depth, v.width);
  }
  if (v.kind == VesselKind::bifurcation) {
    std::printf(", daughters %g and %g at %g deg from %g", v.daughter_diameters[0], v.daughter_diameters[1],
                v.angle_deg, v.center);
  }
  std::printf("\n         meshed with element size %g: %d wall nodes, %d triangles; lumen volume %.4g\n",
              v.element_size, s.vessel->surface.num_points(), s.vessel->surface.num_triangles(), *s.lumen_volume);
  if (s.branches.empty()) {
    std::printf("         branches: not known for a vessel from a file (no branches.csv)\n");
    return;
  }
  std::printf("         branches (branches.csv; flow %s):\n",
              s.branch_flow_by_meter ? "pi a^2 U from the tube meter" : "through each branch's section clearest of the cells");
  const char* names[] = {"parent", "daughter", "daughter"};
  for (std::size_t b = 0; b < s.branches.size(); ++b) {
    const VesselBranch& g = s.branches[b];
    const Eigen::Vector3d n = g.direction();
    Eigen::Vector3d x = g.centre();  // in the box
    for (int d = 0; d < 3; ++d)
      if (const double p = s.vessel->period[d]; p > 0) x[d] -= p * std::floor(x[d] / p);
    std::printf("           %zu%s%s: D = %g, mid-section at [%.4g, %.4g, %.4g], flow along [%.3g, %.3g, %.3g]\n", b,
                v.kind == VesselKind::bifurcation ? " " : "", v.kind == VesselKind::bifurcation ? names[b] : "",
                2 * g.radius, x[0], x[1], x[2], n[0], n[1], n[2]);
  }
}

void print_cells(const Scenario& s) {
  const Case& c = s.c;
  if (!c.cells) {
    std::printf("cells:   none\n");
    return;
  }
  const CaseCells& k = *c.cells;
  std::printf("cells:   %zu %s", s.cells.size(), to_string(k.shape).c_str());
  if (s.tube_hematocrit) std::printf(", tube hematocrit %.3f", *s.tube_hematocrit);
  if (k.hematocrit) std::printf(" (asked %g)", *k.hematocrit);
  if (!k.positions.empty()) {
    std::printf(", at the listed positions, checked against %s\n",
                c.vessel ? "the wall and each other" : "the box and each other");
  } else if (s.placement_note) {
    std::printf(" (seed %d)\n         %s\n", k.seed, s.placement_note->c_str());
  } else {
    std::printf(", placed at random (seed %d)\n", k.seed);
  }
  if (k.perturbation) {
    std::printf("         perturbed by %g Y_%d,%d along the normal\n", k.perturbation->amplitude, k.perturbation->l,
                k.perturbation->m);
  }
  const int n = k.order, m = k.order * k.dealias;
  std::printf("         grid N = %d: %d x %d points, %d modes; de-aliasing M = %d: %d x %d points\n", n, n, 2 * n,
              n * n, m, m, 2 * m);
  std::printf("         membrane %s: Es %g, ", to_string(k.membrane.law).c_str(), k.membrane.shear_modulus);
  if (k.membrane.law != MembraneLawKind::neo_hookean) std::printf("Ed %g, ", k.membrane.dilatation_modulus);
  std::printf("Eb %g\n", k.membrane.bending_modulus);
  const PhysicalUnits si(c.units);
  std::printf("         (Es %.3g N/m, Eb %.3g N m", si.newtons_per_m(k.membrane.shear_modulus),
              si.newton_metres(k.membrane.bending_modulus));
  if (k.membrane.law != MembraneLawKind::neo_hookean)
    std::printf(", Ed %.3g N/m", si.newtons_per_m(k.membrane.dilatation_modulus));
  std::printf(")\n");
  const ReferenceCell ref = reference_cell(k);
  std::printf("         reference cell: area %.4g, volume %.4g\n", ref.area, ref.volume);
}

void print_time(const Scenario& s) {
  const Case& c = s.c;
  const double dt = s.options.dt;
  if (c.cells) {
    const double limit = time_step_limit(*c.cells);
    std::printf("time:    dt limit (37) %.4g (h_eff = sqrt(A)/N = %.4g)\n", limit, effective_spacing(*c.cells));
    if (c.time.dt && *c.time.dt > limit) {
      std::printf("         warning: dt = %g exceeds the limit (37); the run may be unstable\n", *c.time.dt);
    }
  }
  std::printf("         dt %.4g", dt);
  if (!c.time.dt) std::printf(" (auto: %g x limit)", c.time.dt_safety);
  std::printf(", %s, end %g (%.4g ms): %ld steps\n", to_string(c.time.scheme).c_str(), c.time.end,
              PhysicalUnits(c.units).milliseconds(c.time.end), s.steps);
  std::printf("         collision threshold %g, volume constraint %s\n", c.time.collision_threshold,
              c.time.volume_constraint ? "on" : "off");
  if (c.time.contact_range > 0)
    std::printf("         contact repulsion: range %g, strength %g (traction %g at half the range)\n",
                c.time.contact_range, c.time.contact_strength, 0.5 * c.time.contact_strength);
}

void print_output(const Case& c) {
  if (const std::vector<std::string> found = run_files(c.output.dir); !found.empty()) {
    std::printf("warning: %s holds an earlier run (%zu of its files): rbcflow run refuses it without --overwrite\n",
                c.output.dir.string().c_str(), found.size());
  }
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

// The parameters libsolver's chooser picks for each Ewald sum of the run (scenario.h).
void print_ewald(const Scenario& s) {
  std::printf("ewald:   tolerance %g\n", s.c.ewald.tolerance);
  for (const EwaldSum& sum : s.ewald) {
    std::printf("         %s (%ld nodes):\n", sum.what.c_str(), sum.nodes);
    std::istringstream lines(to_string(sum.choice));
    std::string line;
    std::getline(lines, line);  // the heading repeats the kernel and tolerance
    while (std::getline(lines, line)) std::printf("         %s\n", line.c_str());
  }
}

// The estimate of the run's peak memory by part, against its budget (memory_budget.h); on
// several ranks, of each rank against its share of the machine.
void print_memory(const Scenario& s) {
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  const MemoryEstimate& m = s.memory;
  const char* budget = s.c.solver.memory_gib ? "solver.memory_gib" : "the machine's memory";
  if (m.ranks == 1) {
    std::printf("memory:  about %.2f GiB at the peak of a step, of a budget of %.2f GiB (%s)\n", m.total() / kGiB,
                s.memory_budget / kGiB, budget);
  } else {
    std::printf("memory:  on %d ranks, about %.2f GiB on each at the peak of a step, of a budget of %.2f GiB per rank "
                "(%s shared by %d ranks)\n", m.ranks, m.total() / kGiB, s.memory_budget / kGiB, budget,
                s.ranks_per_machine);
  }
  for (const MemoryEstimate::Part& p : m.parts) std::printf("         %-28s %8.3f GiB\n", p.name.c_str(), m.on_each_rank(p) / kGiB);
  std::printf("         (%.1f x the parts, for what a step builds and frees with its freed memory %s, + 60 MB for "
              "the program)\n", m.peak_factor, s.reuses_freed_memory ? "kept" : "returned");
  if (m.kept_coefficients > 0) {
    std::printf("         Ewald pair coefficients %s (%.3f GiB of the cells' Ewald sum)\n",
                s.keeps_pair_coefficients ? "kept between products" : "recomputed in every product to fit the budget",
                m.kept_coefficients / m.ranks / kGiB);
  }
  std::printf("         freed memory %s\n", s.reuses_freed_memory
                                                 ? "kept for the next steps (faster)"
                                                 : "returned to the system: the estimate is above 3/4 of the budget");
  if (s.options.domain.lean_transforms)
    std::printf("         the cells' double layer transformed a component at a time (32 bytes a grid point, not 48)\n");
}

}  // namespace

int run_check(Args& args) {
  if (args.help_requested()) {
    std::printf(
        "usage: rbcflow check CASE.toml [--ranks P]\n"
        "  Validates the case exactly as rbcflow run does before its first step: the vessel is\n"
        "  meshed and checked, the cells placed (or listed), perturbed and checked against the\n"
        "  wall and each other (exit status 2 with file, line and key on an error). Prints the\n"
        "  derived parameters: cell count and tube hematocrit of the meshed lumen, grid sizes, the\n"
        "  time step limit (37), the Ewald parameters the solver will choose, the output, and the\n"
        "  estimate of the run's peak memory by part against its budget (solver.memory_gib or the\n"
        "  machine's memory; a case over it is refused).\n"
        "  --ranks P: the memory estimate of each rank of a run on P ranks (mpirun -np P) that\n"
        "  share this machine (or solver.memory_gib).\n");
    return 0;
  }
  const std::string file = args.positional("case file (CASE.toml)");
  std::string ranks_text;
  std::optional<int> ranks;
  if (args.option("--ranks", ranks_text)) ranks = static_cast<int>(positive_integer("check", "--ranks", ranks_text, 1'000'000));
  args.finish();
  const Case c = read_case(file);
  check_output_dir(c, c.output.dir);
  const Scenario s = prepare_scenario(c, ranks);

  std::printf("case:    %s: \"%s\"\n", file.c_str(), c.title.c_str());
  print_domain(c);
  print_units(c);
  print_vessel(s);
  print_cells(s);
  print_time(s);
  if (c.domain.kind == DomainKind::periodic) print_ewald(s);
  std::printf("solver:  GMRES tolerance %g, at most %d iterations\n", c.solver.gmres_tolerance,
              c.solver.max_iterations);
  if (c.cells) {
    const int radial = c.solver.patch_radial_points.value_or(default_radial_points(c.cells->order));
    std::printf("         singular patches: %d radial x %d angular points (%s)\n", radial, 2 * radial,
                c.solver.patch_radial_points ? "set" : "default, max(8, ceil(3 sqrt(N)))");
  }
  print_output(c);
  print_memory(s);
  std::printf("case OK\n");
  return 0;
}

}  // namespace rbcflow::cli
