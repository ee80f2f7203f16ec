#include "scenario/run.h"

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "io/output_dir.h"
#include "io/plot.h"
#include "io/render.h"
#include "io/vtk_series.h"
#include "io/xdmf_writer.h"
#include "scenario/checkpoint.h"
#include "scenario/derived.h"
#include "scenario/run_output.h"
#include "scenario/scenario.h"

namespace rbcflow {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kMaxVolumeError = 0.01;  // a run whose cells lose 1% of their volume has failed

std::string duration(double seconds) {
  char buf[32];
  const long s = std::lround(seconds);
  if (s >= 3600) {
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  } else if (s >= 60) {
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%.1fs", seconds);
  }
  return buf;
}

// Step, simulated time, seconds per step and ETA: rewritten in place on a terminal, a plain
// line every 5% of the run otherwise.
class Progress {
 public:
  Progress(bool quiet, long first, long last)
      : quiet_(quiet), tty_(isatty(fileno(stdout)) != 0), first_(first), last_(last), start_(Clock::now()) {}
  void update(long step, double time, double step_seconds) {
    if (quiet_) return;
    const long done = step - first_, total = last_ - first_;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    const long every = std::max(1L, total / 20);
    if (!tty_ && done % every != 0 && step != last_) return;
    std::printf("%sstep %ld/%ld  t = %.5g  %.3g s/step  ETA %s%s", tty_ ? "\r" : "", step, last_, time, step_seconds,
                duration(eta).c_str(), tty_ ? "   " : "\n");
    if (tty_ && step == last_) std::printf("\n");
    std::fflush(stdout);
  }

 private:
  bool quiet_, tty_;
  long first_, last_;
  Clock::time_point start_;
};

class RunOutput {
 public:
  RunOutput(const Case& c, std::optional<long> resume)
      : case_(c), dir_(c.output.dir), diagnostics_(dir_ / "diagnostics.csv", resume) {
    if (c.cells) cells_csv_.emplace(dir_ / "cells.csv", resume);
    if (c.output.xdmf) xdmf_.emplace(dir_, resume);
    if (c.output.vtk) vtk_.emplace(dir_, resume);
    render_.field = c.output.render_field;
    render_.view = c.output.render_view;
    render_.width = c.output.render_size[0];
    render_.height = c.output.render_size[1];
    render_.axis = flow_axis(c);
    render_.period = flow_period(c);
    if (!c.cells) render_.field = "none";
  }

  void frame(const CellStepper& stepper, const FlowSolution& s) {
    const std::vector<Surface> surfaces = frame_surfaces(stepper, s);
    if (xdmf_) xdmf_->write_frame(stepper.steps(), stepper.time(), surfaces);
    if (vtk_) vtk_->write_frame(stepper.steps(), stepper.time(), surfaces);
    if (cells_csv_) {
      const bool shear = case_.domain.kind == DomainKind::free && case_.domain.background_flow.kind == FlowKind::shear;
      cells_csv_->write(cell_rows(stepper, s, flow_axis(case_), shear));
    }
  }

  void render(const CellStepper& stepper, const FlowSolution& s) {
    char label[96];
    std::snprintf(label, sizeof label, "step %ld   t = %.4g", stepper.steps(), stepper.time());
    render_.label = label;
    render_png(frame_surfaces(stepper, s), render_, render_path(dir_, stepper.steps()));
  }

  DiagnosticsCsv& diagnostics() { return diagnostics_; }

 private:
  const Case& case_;
  fs::path dir_;
  DiagnosticsCsv diagnostics_;
  std::optional<CellsCsv> cells_csv_;
  std::optional<XdmfWriter> xdmf_;
  std::optional<VtkSeriesWriter> vtk_;
  RenderOptions render_;
};

}  // namespace

void run_case(const RunRequest& request) {
  const Case& c = request.c;
  const bool quiet = request.quiet, render = c.output.render;
  const fs::path& case_file = c.source.file;
  Scenario scenario = prepare_scenario(c);
  const std::unique_ptr<CellStepper> stepper_owner = make_stepper(scenario);
  CellStepper& stepper = *stepper_owner;
  std::optional<long> resume;
  if (!request.restart.empty()) {
    read_checkpoint(stepper, c, request.restart);
    resume = stepper.steps();
  }
  const long first = stepper.steps();
  const long last = request.steps > 0 ? first + request.steps : scenario.steps;
  if (!quiet) {
    std::printf("%s: %zu cells, dt = %.4g%s, steps %ld..%ld, output in %s\n", case_file.c_str(), stepper.cells().size(),
                stepper.dt(), c.time.dt ? "" : " (auto: dt_safety x the limit of (37))", first, last,
                c.output.dir.c_str());
    if (scenario.placement_note) std::printf("%s\n", scenario.placement_note->c_str());
    if (c.domain.tube_velocity) {
      const Eigen::Vector3d& u = stepper.mean_velocity();
      std::printf("tube velocity %g: <u> = [%.6g, %.6g, %.6g] (cell-free wall solve)\n", *c.domain.tube_velocity, u.x(),
                  u.y(), u.z());
    }
    std::fflush(stdout);
  }

  // Only now that the case has been prepared: a case that fails leaves the earlier run as it was.
  if (request.overwrite && !(resume && restarts_in_place(request.restart, c.output.dir))) clear_run(c.output.dir);
  prepare_output_dir(c.output.dir);
  if (resume) {
    if (const auto run = carry_tables_from_checkpoint_run(request.restart, c.output.dir); run && !quiet) {
      std::printf("restart: diagnostics and cell rows up to step %ld carried over from %s\n", *resume, run->c_str());
    }
  }
  write_case_toml(c, c.output.dir / "case.toml");
  RunOutput output(c, resume);
  Progress progress(quiet, first, last);
  std::optional<fs::path> last_checkpoint;
  if (!request.restart.empty()) last_checkpoint = request.restart;
  const int every = c.output.every, render_every = c.output.render_every, checkpoint_every = c.output.checkpoint_every;

  try {
    while (stepper.steps() < last) {
      const long n = stepper.steps();
      const int threads = request.threads_handed_over ? request.threads_handed_over() : 0;
      if (threads > 0 && threads != omp_get_max_threads()) {
        omp_set_num_threads(threads);
        if (!quiet) std::printf("threads: %d from step %ld on (handed over by the study)\n", threads, n);
      }
      const auto t0 = Clock::now();
      const FlowSolution s = stepper.solve();
      const bool resumed_here = resume && n == *resume;  // the run before the restart wrote step n
      if (n % every == 0 && !resumed_here) output.frame(stepper, s);
      if (render && render_every > 0 && n % render_every == 0 && !resumed_here) output.render(stepper, s);
      const StepReport r = stepper.advance(s);
      const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      output.diagnostics().write(diagnostics_row(stepper, r, scenario, seconds));
      if (r.max_volume_error > kMaxVolumeError) {
        char what[160];
        std::snprintf(what, sizeof what, "a cell's volume changed by %.3g%% at step %ld", 100 * r.max_volume_error,
                      stepper.steps());
        throw std::runtime_error(std::string(what).append(" (more than 1%: the run is unstable; try a smaller dt or "
                                                          "more de-aliasing)"));
      }
      if (checkpoint_every > 0 && stepper.steps() % checkpoint_every == 0) {
        last_checkpoint = checkpoint_path(c.output.dir, stepper.steps());
        write_checkpoint(stepper, c, *last_checkpoint);
      }
      progress.update(stepper.steps(), stepper.time(), seconds);
    }
    // The final state: its frame and render (the loop wrote the states before it; a restart
    // that took no step is at the state the earlier run wrote), and its checkpoint when not
    // already written.
    const long n = stepper.steps();
    if (!(resume && n == *resume)) {
      const FlowSolution s = stepper.solve();
      output.frame(stepper, s);
      if (render) output.render(stepper, s);
    }
    if (checkpoint_every > 0 && n % checkpoint_every != 0) {
      last_checkpoint = checkpoint_path(c.output.dir, n);
      write_checkpoint(stepper, c, *last_checkpoint);
    }
    if (render) plot_diagnostics(c.output.dir / "diagnostics.csv", c.output.dir / "diagnostics.png");
  } catch (const std::exception& e) {
    std::string message = e.what();
    message.append(last_checkpoint ? "; the last good checkpoint is " + last_checkpoint->string()
                                   : "; no checkpoint was written");
    throw std::runtime_error(message);
  }
  if (!quiet) std::printf("done: %ld steps, t = %.5g, output in %s\n", last - first, stepper.time(), c.output.dir.c_str());
}

}  // namespace rbcflow
