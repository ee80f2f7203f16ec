// rbcflow study: the tube study of paper section 11.2 (fig. 12, 13) in one command. Runs each
// case (a straight tube with cells), averages its effective viscosity over the statistically
// steady part, and writes DIR/study.csv, DIR/study.png (mu_eff against D with the Pries law
// at the runs' tube hematocrit and its +-10% band) and end and side renders of every tube.
// On bifurcations it is a phase-separation study instead (phase_separation_study.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <omp.h>
#include <optional>
#include <string>
#include <vector>

#include "child_runs.h"
#include "cli.h"
#include "display.h"
#include "io/case.h"
#include "scenario/derived.h"
#include "io/csv.h"
#include "io/output_dir.h"
#include "io/render.h"
#include "io/study_plot.h"
#include "io/vtk_series.h"
#include "io/xdmf_reader.h"
#include "geometry/contact/radial_profile.h"
#include "libsolver/wall/pries_law.h"
#include "scenario/physical_units.h"
#include "scenario/run.h"
#include "phase_separation_study.h"
#include "study_analysis.h"

namespace rbcflow::cli {
namespace {

namespace fs = std::filesystem;

constexpr double kBand = 0.10;  // the Pries law's band in the plot

// `discharge_hematocrit` and `pries` use Pries's own H_T -> H_D conversion; the columns from
// `tube_velocity` on are the run's own measurements over the averaged rows, in the physical
// units of the case's [units] where named so (empty for runs without those diagnostics).
const std::vector<std::string>& study_columns() {
  static const std::vector<std::string> c = {
      "case", "diameter", "diameter_um", "tube_hematocrit", "discharge_hematocrit", "order", "cells", "steps",
      "time", "steady_from", "rows_averaged", "effective_viscosity", "effective_viscosity_stderr", "pries",
      "pressure_gradient_fluctuation", "effective_viscosity_drift", "tube_velocity", "tube_velocity_mm_per_s",
      "pseudo_shear_rate_per_s", "discharge_hematocrit_measured", "pries_at_measured_hd", "max_area_strain",
      "apparent_viscosity_mpas", "wall_shear_stress_pa", "pressure_gradient_pa_per_um", "time_ms", "cell_free_layer",
      "cell_free_layer_um", "min_wall_gap", "wall_element_size"};
  return c;
}

// The measured columns of study.csv (from tube_velocity on) for a run's steady average.
std::vector<std::string> measured_columns(const Case& c, const SteadyAverage& a) {
  const PhysicalUnits si(c.units);
  const double D = c.vessel->diameter, G = -a.pressure_gradient;
  std::vector<std::string> out;
  if (a.tube_velocity) {
    out = {csv_number(*a.tube_velocity), csv_number(si.mm_per_s(*a.tube_velocity)),
           csv_number(si.per_second(*a.tube_velocity / D))};
  } else {
    out = {"", "", ""};
  }
  if (a.discharge_hematocrit) {
    out.push_back(csv_number(*a.discharge_hematocrit));
    out.push_back(csv_number(pries_relative_viscosity(si.micrometres(D), *a.discharge_hematocrit)));
  } else {
    out.insert(out.end(), {"", ""});
  }
  out.push_back(csv_number(a.max_area_strain));
  // The wall carries the pressure drop: tau_w = G D / 4 with cells as without.
  out.push_back(csv_number(si.mpa_s(a.mean)));
  out.push_back(csv_number(si.pascals(G * D / 4)));
  out.push_back(csv_number(si.pa_per_um(G)));
  out.push_back(csv_number(si.milliseconds(a.to_time)));
  out.push_back(csv_number(a.cell_free_layer));
  out.push_back(a.cell_free_layer ? csv_number(si.micrometres(*a.cell_free_layer)) : "");
  out.push_back(csv_number(a.min_wall_gap));
  out.push_back(csv_number(c.vessel->element_size));
  return out;
}

double parse_number(const std::string& text, const std::string& what, double lo, double hi) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !(v >= lo && v <= hi)) {
    throw UsageError("rbcflow study: " + what + " must be a number in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "], got '" + text + "'");
  }
  return v;
}

void render_tube(const fs::path& run_dir, const Case& c, const fs::path& out, const std::string& stem) {
  const VtkFrame frame = read_vtk_frame(run_dir);
  RenderOptions o;
  o.field = c.output.render_field;
  o.axis = c.vessel->axis;
  o.period = flow_period(c);
  o.width = c.output.render_size[0];
  o.height = c.output.render_size[1];
  char label[128];
  const PhysicalUnits si(c.units);
  std::snprintf(label, sizeof label, "D = %.2f um   step %ld   t = %.4g (%.4g ms)", si.micrometres(c.vessel->diameter),
                frame.step, frame.time, si.milliseconds(frame.time));
  o.label = label;
  for (const RenderView view : {RenderView::end, RenderView::side}) {
    o.view = view;
    render_png(frame.surfaces, o, out / "renders" / (stem + "_" + to_string(view) + ".png"));
  }
}

// The radial hematocrit profile of a run (geometry/contact/radial_profile.h): the cells' volume
// fraction in 20 annuli, averaged over the XDMF frames of the steady part (the last frame when
// none falls in it); empty without XDMF frames.
constexpr int kProfileBins = 20;
constexpr double kProfileSpacing = 0.1;

std::vector<double> radial_hematocrit(const Case& c, const fs::path& run_dir, double from_time) {
  if (!c.output.xdmf) return {};
  std::vector<XdmfFrameTime> frames = read_xdmf_frames(run_dir);
  std::vector<XdmfFrameTime> steady;
  for (const XdmfFrameTime& f : frames)
    if (f.time >= from_time) steady.push_back(f);
  if (steady.empty() && !frames.empty()) steady.push_back(frames.back());
  RadialProfileSpec spec;
  spec.axis = c.vessel->axis;
  spec.axis_point = 0.5 * Eigen::Vector3d(c.domain.box[0], c.domain.box[1], c.domain.box[2]);
  spec.radius = 0.5 * c.vessel->diameter;
  spec.period = c.domain.box[spec.axis];
  spec.bins = kProfileBins;
  spec.spacing = kProfileSpacing;
  std::vector<double> mean(kProfileBins, 0.0);
  for (const XdmfFrameTime& f : steady) {
    const XdmfFrame frame = read_xdmf_frame(run_dir, f.step);
    for (const Surface& s : frame.surfaces) {
      if (s.name != "cells") continue;
      const auto id = std::find_if(s.fields.begin(), s.fields.end(), [](const SurfaceField& x) { return x.name == "cell"; });
      if (id == s.fields.end()) throw std::runtime_error(run_dir.string() + ": the cells' surface has no cell field");
      const Eigen::VectorXi component = id->values.col(0).array().round().cast<int>();
      const std::vector<double> f_i = radial_volume_fraction(s.mesh, component, spec);
      for (int i = 0; i < kProfileBins; ++i) mean[i] += f_i[i] / static_cast<double>(steady.size());
    }
  }
  return steady.empty() ? std::vector<double>{} : mean;
}

// The last step of a run of `c` that `dir` holds, or 0 where it holds none: its case.toml is
// the one this run would write up to output.dir (a run made into another directory and moved
// or linked there counts) and its diagnostics have a row.
long last_step_of_run(const Case& c, const fs::path& dir) {
  std::ifstream in(dir / "case.toml", std::ios::binary);
  if (!in || !fs::is_regular_file(dir / "diagnostics.csv")) return 0;
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Case here = c;
  try {
    here.output.dir = parse_case(written, dir / "case.toml").output.dir;
  } catch (const InputError&) {
    return 0;  // not a case file rbcflow wrote: run again
  }
  if (written != case_toml(here)) return 0;
  const CsvTable d = read_csv(dir / "diagnostics.csv");
  return d.rows.empty() ? 0 : std::stol(d.rows.back()[d.column("step")]);
}

// Whether `dir` holds a finished run of `c`: its diagnostics reach the last step (`steps`, or
// time.end).
bool finished_run(const Case& c, const fs::path& dir, long steps) {
  const long last = steps > 0 ? steps : std::max(1L, static_cast<long>(std::ceil(c.time.end / time_step(c) - 1e-9)));
  return last_step_of_run(c, dir) == last;
}

// The last non-empty line of a log: a failed run's error message.
std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  return last.empty() ? "no message in " + log.string() : last;
}

// Runs the cases not reused as `rbcflow run` processes, `jobs` at a time, each with its share
// of the threads and its output in DIR/<case>.log; a failed run's message goes to failure[k].
void run_side_by_side(const std::vector<Case>& cases, const std::vector<fs::path>& case_files,
                      const std::vector<bool>& reused, const std::string& steps_text, const fs::path& out, int jobs,
                      bool quiet, std::vector<std::string>& failure) {
  std::vector<ChildRun> runs;
  std::vector<std::size_t> which;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (reused[k]) continue;
    ChildRun r;
    r.args = {"run", case_files[k].string(), "--out", cases[k].output.dir.string(), "--overwrite"};
    if (!steps_text.empty()) r.args.insert(r.args.end(), {"--steps", steps_text});
    r.log = out / (case_files[k].stem().string() + ".log");
    runs.push_back(std::move(r));
    which.push_back(k);
  }
  if (runs.empty()) return;
  const int threads = initial_threads(jobs, runs.size(), omp_get_max_threads());
  const int at_once = static_cast<int>(std::min<std::size_t>(jobs, runs.size()));
  if (!quiet) {
    std::printf("running %zu case%s, %d at a time with %d thread%s each; logs in %s/<case>.log\n", runs.size(),
                runs.size() == 1 ? "" : "s", at_once, threads, threads == 1 ? "" : "s", out.c_str());
  }
  std::fflush(stdout);
  const auto started = [&](std::size_t i) {
    if (!quiet) std::printf("== %s: started\n", case_files[which[i]].stem().c_str());
    std::fflush(stdout);
  };
  const auto done = [&](std::size_t i, const ChildResult& r) {
    const std::size_t k = which[i];
    if (r.exit_status != 0) {
      failure[k] = "exit status " + std::to_string(r.exit_status) + ": " + last_line(runs[i].log);
    }
    if (!quiet) {
      std::printf("== %s: %s after %.0f s\n", case_files[k].stem().c_str(), r.exit_status == 0 ? "finished" : "failed",
                  r.seconds);
    }
    std::fflush(stdout);
  };
  run_children(runs, jobs, omp_get_max_threads(), started, done);
}

// study.png, radial_hematocrit.png and the closing line of a tube study.
void finish_tube_study(StudyPlot& plot, const std::vector<double>& measured_hd, const CurvesPlot& profiles,
                       double hematocrit_sum, const std::string& out) {
  if (plot.diameter.empty()) throw std::runtime_error("rbcflow study: every run failed; nothing to plot");
  const double ht = hematocrit_sum / static_cast<double>(plot.diameter.size());
  const auto [lo, hi] = std::minmax_element(plot.diameter.begin(), plot.diameter.end());
  const double d0 = std::max(1.0, *lo - 1.0), d1 = *hi + 1.0;
  for (int i = 0; i <= 200; ++i) {
    const double d = d0 + (d1 - d0) * i / 200.0;
    const double mu = pries_relative_viscosity(d, discharge_hematocrit(d, ht));
    plot.reference_diameter.push_back(d);
    plot.reference.push_back(mu);
    plot.reference_low.push_back((1 - kBand) * mu);
    plot.reference_high.push_back((1 + kBand) * mu);
  }
  char title[96];
  std::snprintf(title, sizeof title, "Effective viscosity at tube hematocrit %.2f", ht);
  plot.title = title;
  plot.reference_name = "Pries et al. 1992";
  if (std::none_of(measured_hd.begin(), measured_hd.end(), [](double v) { return v < 0; })) {
    plot.reference_at_points = measured_hd;
    plot.reference_at_points_name = "Pries at the measured H_D";
  }
  plot_study(plot, fs::path(out) / "study.png");
  if (!profiles.names.empty()) plot_curves(profiles, fs::path(out) / "radial_hematocrit.png");
  std::printf("study: %s/study.csv, %s/study.png, renders in %s/renders\n", out.c_str(), out.c_str(), out.c_str());
}

void print_help() {
  std::printf(
      "usage: rbcflow study CASE.toml... -o DIR [--steady-fraction F] [--steps N] [--reuse | --so-far] [--jobs J]\n"
      "                     [--quiet]\n"
      "  Runs every case (straight tubes with cells, e.g. data/cases/fahraeus/quick/*.toml) into\n"
      "  DIR/<case name>/, averages the effective viscosity (45)-(46) over time >= F x the run's\n"
      "  end (default F = 0.5) with a batch-means standard error, and writes DIR/study.csv,\n"
      "  DIR/study.png (mu_eff against D in um, with the Pries law at the runs' tube hematocrit,\n"
      "  converted to the discharge hematocrit, and its +-10%% band), DIR/renders/<case>_end.png\n"
      "  and _side.png (fig. 12), and each tube's radial hematocrit (DIR/<case>_radial_hematocrit.csv,\n"
      "  all of them in DIR/radial_hematocrit.png). study.csv also holds each run's measured tube\n"
      "  velocity, discharge hematocrit, area strain and cell-free layer, and physical units.\n"
      "  --steps N runs N steps of each case instead of to time.end.\n"
      "  A case that is run replaces what DIR/<case name>/ held (rbcflow run --overwrite).\n"
      "  --reuse takes a case's finished run from DIR/<case name>/ instead of running it again\n"
      "  (same case.toml, diagnostics to the last step): to add cases to a sweep, or to collect\n"
      "  runs made separately with rbcflow run CASE.toml --out DIR/<case name> (or moved there).\n"
      "  --so-far runs nothing: it takes every case's run in DIR/<case name>/ (same case.toml) as\n"
      "  far as it has gone, for a look at long runs still in progress (continued in pieces from\n"
      "  their checkpoints); a case without a run there is an error.\n"
      "  --jobs J runs J cases at a time, each as its own rbcflow run process with its share of the\n"
      "  threads (OMP_NUM_THREADS / J) and its output in DIR/<case name>.log: faster than one case\n"
      "  after another when a case leaves cores idle (list the longest cases first). Once the last\n"
      "  case has started, the runs still going take over the threads of those that finished.\n"
      "  A run that fails (blow-up) is reported and left out; the others are still collected,\n"
      "  and the exit status is then 1.\n"
      "  Bifurcation cases (all of one kind) make a phase-separation study instead: each run's\n"
      "  daughter alpha (branch 1) share of the parent's blood flow and of its red cells (passages\n"
      "  through the daughters' mid-sections, branches.csv) over the steady part, with a binomial\n"
      "  standard error and Wilson 68%% interval (the plot's bars), against the law of Pries et\n"
      "  al. 2005 at the run's diameters and the parent's measured discharge hematocrit:\n"
      "  DIR/phase_separation.csv and .png.\n");
}

}  // namespace

int run_study(Args& args) {
  if (args.help_requested()) {
    print_help();
    return 0;
  }
  std::string out, fraction_text, steps_text, jobs_text;
  if (!args.option("-o", out)) throw UsageError("rbcflow study: missing -o DIR");
  const bool quiet = args.flag("--quiet"), reuse = args.flag("--reuse"), so_far = args.flag("--so-far");
  args.option("--steady-fraction", fraction_text);
  args.option("--steps", steps_text);
  args.option("--jobs", jobs_text);
  std::vector<fs::path> case_files{args.positional("case file (CASE.toml)")};
  for (std::string more; !(more = args.next_positional()).empty();) case_files.emplace_back(more);
  args.finish();
  const double fraction = fraction_text.empty() ? 0.5 : parse_number(fraction_text, "--steady-fraction", 0.0, 1.0);
  const long steps = steps_text.empty() ? 0 : static_cast<long>(parse_number(steps_text, "--steps", 1, 1e9));
  if (so_far && (reuse || !steps_text.empty()))
    throw UsageError("rbcflow study: --so-far takes the runs as they are; it goes with neither --reuse nor --steps");
  const double jobs_value = jobs_text.empty() ? 1 : parse_number(jobs_text, "--jobs", 1, 256);
  if (jobs_value != std::floor(jobs_value)) throw UsageError("rbcflow study: --jobs must be a whole number, got '" + jobs_text + "'");
  const int jobs = static_cast<int>(jobs_value);

  // Every case is read and checked before the first (long) run.
  std::vector<Case> cases;
  for (const fs::path& f : case_files) {
    Case c = read_case(f);
    if (!c.vessel || (c.vessel->kind != VesselKind::tube && c.vessel->kind != VesselKind::bifurcation))
      throw case_error(c, "vessel", "a study needs a straight tube or a bifurcation");
    if (!cases.empty() && c.vessel->kind != cases.front().vessel->kind)
      throw case_error(c, "vessel", "a study's cases are all tubes or all bifurcations; " + case_files.front().string() +
                                        " is a " + to_string(cases.front().vessel->kind));
    if (!c.cells) throw case_error(c, "cells", "a study needs cells");
    c.output.dir = fs::path(out) / f.stem();
    check_output_dir(c, c.output.dir);
    if (so_far && last_step_of_run(c, c.output.dir) == 0) {  // before anything is started or written
      const fs::path& dir = c.output.dir;
      throw InputError(f.string() + ": --so-far: " + dir.string() + " holds no run of this case (" +
                       (fs::is_regular_file(dir / "case.toml") && fs::is_regular_file(dir / "diagnostics.csv")
                            ? "its case.toml is another case's"
                            : "no case.toml and diagnostics.csv") +
                       ")");
    }
    cases.push_back(std::move(c));
  }
  ensure_display();  // renders and the plot
  fs::create_directories(fs::path(out) / "renders");

  std::vector<bool> reused(cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k)
    reused[k] = so_far || (reuse && finished_run(cases[k], cases[k].output.dir, steps));
  // With --jobs, the runs first, side by side; their failures are collected below.
  std::vector<std::string> child_failure(cases.size());
  if (jobs > 1) run_side_by_side(cases, case_files, reused, steps_text, fs::path(out), jobs, quiet, child_failure);

  const bool bifurcations = cases.front().vessel->kind == VesselKind::bifurcation;
  PhaseSeparationStudy split(fs::path(out), quiet);
  std::optional<CsvWriter> csv;
  if (!bifurcations) csv.emplace(fs::path(out) / "study.csv", study_columns());
  StudyPlot plot;
  std::vector<double> measured_hd;  // Pries at each run's measured H_D (-1: not measured)
  CurvesPlot profiles;
  profiles.title = "Radial hematocrit (volume fraction of cells, steady part)";
  profiles.x_title = "r / R";
  profiles.y_title = "hematocrit";
  double hematocrit_sum = 0;
  std::vector<std::string> failed;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const std::string stem = case_files[k].stem().string();
    if (!quiet && jobs == 1) std::printf("== %s (%zu of %zu)\n", stem.c_str(), k + 1, cases.size());
    std::fflush(stdout);
    if (reused[k]) {
      if (!quiet && so_far) {
        std::printf("taking the run in %s as far as it has gone (step %ld)\n", c.output.dir.c_str(),
                    last_step_of_run(c, c.output.dir));
      } else if (!quiet) {
        std::printf("reusing the finished run in %s\n", c.output.dir.c_str());
      }
    } else if (!child_failure[k].empty()) {
      std::fprintf(stderr, "rbcflow study: %s failed, left out of the study: %s\n", stem.c_str(), child_failure[k].c_str());
      failed.push_back(stem);
      continue;
    } else if (jobs == 1) {
      try {
        RunRequest request;
        request.c = c;
        request.steps = steps;
        request.quiet = quiet;
        request.overwrite = true;  // the study owns DIR/<case name>/
        run_case(request);
      } catch (const InputError&) {
        throw;
      } catch (const std::runtime_error& e) {  // the run failed (blow-up, unconverged GMRES): go on
        std::fprintf(stderr, "rbcflow study: %s failed, left out of the study: %s\n", stem.c_str(), e.what());
        failed.push_back(stem);
        continue;
      }
    }
    if (bifurcations) {
      split.add(c, stem, fraction);
      continue;
    }
    const SteadyAverage a = steady_average(c.output.dir / "diagnostics.csv", c.vessel->axis, fraction);
    const CsvTable diagnostics = read_csv(c.output.dir / "diagnostics.csv");
    const double ht = std::stod(diagnostics.rows.front()[diagnostics.column("tube_hematocrit")]);
    const double d_um = PhysicalUnits(c.units).micrometres(c.vessel->diameter);
    const double hd = discharge_hematocrit(d_um, ht);
    const double pries = pries_relative_viscosity(d_um, hd);
    const CsvTable cells = read_csv(c.output.dir / "cells.csv");
    const long n_cells = std::count_if(cells.rows.begin(), cells.rows.end(),
                                       [&](const auto& r) { return r[0] == cells.rows.front()[0]; });
    std::vector<std::string> row = {
        stem, csv_number(c.vessel->diameter), csv_number(d_um), csv_number(ht), csv_number(hd),
        std::to_string(c.cells->order), std::to_string(n_cells), std::to_string(diagnostics.rows.size()),
        csv_number(a.to_time), csv_number(a.from_time), std::to_string(a.rows), csv_number(a.mean),
        csv_number(a.standard_error), csv_number(pries), csv_number(a.pressure_gradient_fluctuation), csv_number(a.drift)};
    const std::vector<std::string> measured = measured_columns(c, a);
    row.insert(row.end(), measured.begin(), measured.end());
    csv->write(row);
    if (c.output.vtk) render_tube(c.output.dir, c, out, stem);
    if (const std::vector<double> h = radial_hematocrit(c, c.output.dir, a.from_time); !h.empty()) {
      const PhysicalUnits si(c.units);
      const double width = 0.5 * c.vessel->diameter / kProfileBins;
      CsvWriter profile(fs::path(out) / (stem + "_radial_hematocrit.csv"), {"r", "r_um", "r_over_radius", "hematocrit"});
      std::vector<double> x, y;
      double cross_section = 0.0;  // the area-weighted mean: the tube hematocrit of the frames
      for (int i = 0; i < kProfileBins; ++i) {
        const double r = (i + 0.5) * width;
        profile.write({csv_number(r), csv_number(si.micrometres(r)), csv_number(r / (0.5 * c.vessel->diameter)),
                       csv_number(h[i])});
        x.push_back(r / (0.5 * c.vessel->diameter));
        y.push_back(h[i]);
        cross_section += h[i] * (2 * i + 1) / (kProfileBins * kProfileBins);
      }
      profiles.names.push_back(stem + " (D = " + csv_number(std::round(d_um * 100) / 100) + " um)");
      profiles.x.push_back(std::move(x));
      profiles.y.push_back(std::move(y));
      if (!quiet) {
        std::printf("%s: radial hematocrit in %s_radial_hematocrit.csv (its area-weighted mean %.3f; H_T %.3f)\n",
                    stem.c_str(), stem.c_str(), cross_section, ht);
      }
    }
    plot.diameter.push_back(d_um);
    plot.value.push_back(a.mean);
    plot.bar_low.push_back(a.mean - a.standard_error);
    plot.bar_high.push_back(a.mean + a.standard_error);
    measured_hd.push_back(a.discharge_hematocrit ? pries_relative_viscosity(d_um, *a.discharge_hematocrit) : -1.0);
    hematocrit_sum += ht;
    std::printf("%s: D = %.2f um, H_T = %.3f (H_D = %.3f): mu_eff = %.4f +- %.4f over t in [%.4g, %.4g] (%ld rows), "
                "drift %+.2f%%; Pries %.4f; <grad p> fluctuation %.2f%%\n",
                stem.c_str(), d_um, ht, hd, a.mean, a.standard_error, a.from_time, a.to_time, a.rows, 100 * a.drift,
                pries, 100 * a.pressure_gradient_fluctuation);
    if (a.tube_velocity && a.discharge_hematocrit) {
      const PhysicalUnits si(c.units);
      std::printf("%s: U = %.3g mm/s (U/D %.3g 1/s), measured H_D = %.3f: Pries %.4f; max area strain %.3g\n",
                  stem.c_str(), si.mm_per_s(*a.tube_velocity), si.per_second(*a.tube_velocity / c.vessel->diameter),
                  *a.discharge_hematocrit, pries_relative_viscosity(d_um, *a.discharge_hematocrit),
                  a.max_area_strain.value_or(0));
    }
  }
  if (bifurcations) {
    split.finish();
  } else {
    finish_tube_study(plot, measured_hd, profiles, hematocrit_sum, out);
  }
  if (failed.empty()) return 0;
  std::string names;
  for (const std::string& f : failed) names.append(names.empty() ? "" : ", ").append(f);
  std::fprintf(stderr, "rbcflow study: %zu of %zu runs failed and are left out: %s\n", failed.size(), cases.size(),
               names.c_str());
  return 1;
}

}  // namespace rbcflow::cli
