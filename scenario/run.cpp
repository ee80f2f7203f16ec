#include "scenario/run.h"

#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "io/output_dir.h"
#include "io/plot.h"
#include "io/render.h"
#include "io/vtk_series.h"
#include "io/xdmf_writer.h"
#include "libsolver/parallel/communicator.h"
#include "libsolver/parallel/ownership.h"
#include "scenario/branch_monitor.h"
#include "scenario/checkpoint.h"
#include "scenario/derived.h"
#include "scenario/physical_units.h"
#include "scenario/run_output.h"
#include "scenario/shared_output.h"
#include "scenario/scenario.h"

namespace rbcflow {
namespace {

// This rank's part of a frame of rbcflow.h5 that the ranks write together: the cells begin ..
// end - 1 of the surface "cells" (XdmfWriter::SurfacePart).
struct FramePart {
  int begin = 0, end = 0;
  std::map<std::string, XdmfWriter::SurfacePart> surfaces;
};

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

// The cells_passed of each branch in branches.csv's rows of `step` (a restart continues the
// counts); zeros where the file or the rows are missing (a run of an earlier version).
std::vector<long> passed_at(const fs::path& path, long step, std::size_t branches) {
  std::vector<long> passed(branches, 0);
  if (!fs::exists(path)) return passed;
  const CsvTable t = read_csv(path);
  const std::size_t s = t.column("step"), b = t.column("branch"), p = t.column("cells_passed");
  for (const auto& row : t.rows) {
    if (std::stol(row[s]) != step) continue;
    const std::size_t i = std::stoul(row[b]);
    if (i < branches) passed[i] = std::stol(row[p]);
  }
  return passed;
}

class RunOutput {
 public:
  // `frame_ranks`: the ranks that write rbcflow.h5 together (shared_output.h), if they do;
  // `centroids`: the cells' volume centroids at the start, where the vessel has branches.
  RunOutput(const Case& c, const Scenario& s, std::optional<long> resume,
            const std::optional<XdmfWriter::Ranks>& frame_ranks, const std::vector<Eigen::Vector3d>& centroids)
      : dir_(c.output.dir), diagnostics_(dir_ / "diagnostics.csv", resume), render_(render_options(c)) {
    if (c.cells) cells_csv_.emplace(dir_ / "cells.csv", resume);
    if (!s.branches.empty()) {
      branches_csv_.emplace(dir_ / "branches.csv", resume);
      const std::vector<long> passed = resume ? passed_at(dir_ / "branches.csv", *resume, s.branches.size()) : std::vector<long>{};
      const std::optional<double> tube_area =
          s.branch_flow_by_meter ? std::optional<double>(std::numbers::pi * s.options.tube->radius * s.options.tube->radius)
                         : std::nullopt;
      branches_.emplace(s.branches, s.vessel->period, tube_area, centroids, passed);
    }
    if (c.output.xdmf) xdmf_.emplace(dir_, resume, "rbcflow", frame_ranks);
    if (c.output.vtk) vtk_.emplace(dir_, resume);
  }

  // `rows`: cells.csv's rows of the frame (frame_cell_rows); `cells`: every cell's state;
  // `part`: this rank's part of rbcflow.h5's frame where the ranks write it together.
  void frame(const CellStepper& stepper, const FlowSolution& s, const std::vector<CellRow>& rows,
             const CellsForOutput& cells, const std::optional<FramePart>& part) {
    if (xdmf_ && part) {
      xdmf_->write_frame(stepper.steps(), stepper.time(), frame_surfaces(stepper, s, cells, part->begin, part->end),
                         part->surfaces);
    }
    if (vtk_ || (xdmf_ && !part)) {
      const std::vector<Surface> surfaces =
          frame_surfaces(stepper, s, cells, 0, static_cast<int>(stepper.cells().size()));
      if (xdmf_ && !part) xdmf_->write_frame(stepper.steps(), stepper.time(), surfaces);
      if (vtk_) vtk_->write_frame(stepper.steps(), stepper.time(), surfaces);
    }
    if (cells_csv_) cells_csv_->write(rows);
  }

  void render(const CellStepper& stepper, const FlowSolution& s, const CellsForOutput& cells) {
    char label[96];
    std::snprintf(label, sizeof label, "step %ld   t = %.4g", stepper.steps(), stepper.time());
    render_.label = label;
    render_png(frame_surfaces(stepper, s, cells, 0, static_cast<int>(stepper.cells().size())), render_,
               render_path(dir_, stepper.steps()));
  }

  bool writes_vtk() const { return vtk_.has_value(); }

  DiagnosticsCsv& diagnostics() { return diagnostics_; }

  // branches.csv after a step (a vessel with known branches), the cells' volume centroids then
  // at `centroids`.
  void branches(const CellStepper& stepper, const StepReport& report, const std::vector<Eigen::Vector3d>& centroids) {
    if (branches_) branches_csv_->write(branches_->update(stepper.steps(), stepper.time(), report, centroids));
  }

 private:
  fs::path dir_;
  DiagnosticsCsv diagnostics_;
  std::optional<CellsCsv> cells_csv_;
  std::optional<BranchesCsv> branches_csv_;
  std::optional<BranchMonitor> branches_;
  std::optional<XdmfWriter> xdmf_;
  std::optional<VtkSeriesWriter> vtk_;
  RenderOptions render_;
};

}  // namespace

struct Run::State {
  RunRequest request;
  // On several ranks every rank steps the same replicated state; rank 0 writes and prints, and
  // with parallel HDF5 the ranks write the frames of rbcflow.h5 and the checkpoints together.
  Communicator ranks = Communicator::world();
  Scenario scenario;
  std::unique_ptr<CellStepper> stepper;
  std::optional<long> resume;
  long first = 0, last = 0;
  std::optional<RunOutput> output;        // rank 0
  std::optional<XdmfWriter> other_frames;  // the other ranks' part of rbcflow.h5
  std::optional<XdmfWriter::Ranks> frame_ranks;  // the ranks that write rbcflow.h5 together
  std::optional<Progress> progress;
  std::optional<fs::path> last_checkpoint;

  // cells.csv's rows of a frame, a case with cells (none otherwise). Collective: each rank
  // measures its own cells.
  std::vector<CellRow> frame_cell_rows(const CellStepper& stepper, const FlowSolution& s) const {
    const Case& c = request.c;
    if (!c.cells) return {};
    const bool shear = c.domain.kind == DomainKind::free && c.domain.background_flow.kind == FlowKind::shear;
    return cell_rows(stepper, s, flow_axis(c), shear);
  }

  // This rank's part of a frame of rbcflow.h5 that the ranks write together: its block of the
  // cells (shared_output.h), none where rank 0 writes the frames alone.
  std::optional<FramePart> frame_part(const CellStepper& stepper) const {
    if (!(request.c.output.xdmf && frame_ranks)) return std::nullopt;
    const int nc = static_cast<int>(stepper.cells().size());
    const OwnedRange block = owned_block(nc, ranks);
    const long points = cell_frame_points(stepper), triangles = cell_frame_triangles(stepper);
    FramePart part{block.begin, block.end, {}};
    if (nc > 0)
      part.surfaces["cells"] = XdmfWriter::SurfacePart{block.begin * points, nc * points, block.begin * triangles,
                                                       nc * triangles};
    return part;
  }

  // A frame and a render, as the step asks: every rank calls it. The cells' state is brought to
  // the ranks that write it (CellStepper::cells_for_output): rank 0 every cell for the VTK
  // frames, a render or the frames of rbcflow.h5 it writes alone, each rank its block for the
  // frames the ranks write together.
  void output_state(const CellStepper& stepper, const FlowSolution& s, bool frame_now, bool render_now) {
    const std::optional<FramePart> part = frame_now ? frame_part(stepper) : std::nullopt;
    const int nc = static_cast<int>(stepper.cells().size());
    const bool every_cell = output && ((frame_now && (output->writes_vtk() || (request.c.output.xdmf && !part))) ||
                                       render_now);
    std::vector<int> cells;
    if (every_cell) {
      for (int c = 0; c < nc; ++c) cells.push_back(c);
    } else if (part) {
      for (int c = part->begin; c < part->end; ++c) cells.push_back(c);
    }
    const CellsForOutput state = stepper.cells_for_output(s, cells);
    if (frame_now) {
      const std::vector<CellRow> rows = frame_cell_rows(stepper, s);
      if (output) {
        output->frame(stepper, s, rows, state, part);
      } else if (other_frames) {
        other_frames->write_frame(stepper.steps(), stepper.time(),
                                  frame_surfaces(stepper, s, state, part->begin, part->end), part->surfaces);
      }
    }
    if (output && render_now) output->render(stepper, s, state);
  }

  // The cells' volume centroids where the vessel has branches (branches.csv), none elsewhere.
  // Collective: every rank calls it.
  std::vector<Eigen::Vector3d> branch_centroids() const {
    return scenario.branches.empty() ? std::vector<Eigen::Vector3d>{} : stepper->volume_centroids();
  }

  // Runs `f`; an exception leaves with the last good checkpoint named.
  template <typename F>
  void guarded(F f) {
    try {
      f();
    } catch (const std::exception& e) {
      std::string message = e.what();
      message.append(last_checkpoint ? "; the last good checkpoint is " + last_checkpoint->string() +
                                           " (a restart from it may change time.dt, time.dt_safety, cells.order "
                                           "and cells.dealias)"
                                     : "; no checkpoint was written");
      throw std::runtime_error(message);
    }
  }
};

Run::Run(RunRequest request) : state_(std::make_unique<State>()) {
  State& r = *state_;
  r.request = std::move(request);
  const Case& c = r.request.c;
  const bool quiet = r.request.quiet;
  // A restart may change the discretisation (checkpoint.h): its cells are placed as the
  // checkpoint's run placed them, at that run's order.
  std::vector<std::string> rediscretised, contact_changes;
  std::optional<int> placed_at_order;
  if (!r.request.restart.empty()) {
    const Case run = as_run_of_checkpoint(c, r.request.restart);
    rediscretised = rediscretised_keys(run, c);
    contact_changes = contact_keys(run, c);
    if (run.cells) placed_at_order = run.cells->order;
  }
  r.scenario = prepare_scenario(c, std::nullopt, placed_at_order);
  r.stepper = make_stepper(r.scenario);
  CellStepper& stepper = *r.stepper;
  if (!r.request.restart.empty()) {
    read_checkpoint(stepper, c, r.request.restart);
    r.resume = stepper.steps();
    r.last_checkpoint = r.request.restart;
  }
  r.first = stepper.steps();
  r.last = r.request.steps > 0 ? r.first + r.request.steps : r.scenario.steps;
  const bool root = r.ranks.root();
  if (!quiet && root) {
    std::printf("%s: %zu cells, dt = %.4g%s, steps %ld..%ld, output in %s\n", c.source.file.c_str(),
                stepper.cells().size(), stepper.dt(), c.time.dt ? "" : " (auto: dt_safety x the limit of (37))", r.first,
                r.last, c.output.dir.c_str());
    std::printf("parallel: %s\n", ranks_and_threads(r.ranks.size(), omp_get_max_threads()).c_str());
    if (!rediscretised.empty()) {
      std::string changes;
      for (const std::string& k : rediscretised) changes += (changes.empty() ? "" : ", ") + k;
      std::printf("restart at another discretisation: %s (shapes resampled, step history started afresh)\n",
                  changes.c_str());
    }
    if (!contact_changes.empty()) {
      std::string changes;
      for (const std::string& k : contact_changes) changes += (changes.empty() ? "" : ", ") + k;
      std::printf("restart with another contact repulsion: %s\n", changes.c_str());
    }
    if (r.scenario.placement_note) std::printf("%s\n", r.scenario.placement_note->c_str());
    if (const std::optional<double> U = r.scenario.options.tube_velocity) {
      const Eigen::Vector3d& u = stepper.mean_velocity();
      const PhysicalUnits si(c.units);
      std::printf("tube velocity %.4g (%.3g mm/s, U/D %.3g 1/s), held every step; without cells <u> = [%.6g, %.6g, "
                  "%.6g]\n", *U, si.mm_per_s(*U), si.per_second(*U / c.vessel->diameter), u.x(), u.y(), u.z());
    }
    std::fflush(stdout);
  }

  r.progress.emplace(quiet || !root, r.first, r.last);
  if (root) {
    // Only now that the case has been prepared: a case that fails leaves the earlier run as it was.
    if (r.request.overwrite && !(r.resume && restarts_in_place(r.request.restart, c.output.dir))) {
      clear_run(c.output.dir);
    }
    prepare_output_dir(c.output.dir);
    if (r.resume) {
      if (const auto run = carry_tables_from_checkpoint_run(r.request.restart, c.output.dir); run && !quiet) {
        std::printf("restart: diagnostics and cell rows up to step %ld carried over from %s\n", *r.resume, run->c_str());
      }
    }
    write_case_toml(c, c.output.dir / "case.toml");
  }
  r.frame_ranks = frame_writers(r.ranks, static_cast<long>(stepper.cells().size()));
  const std::optional<XdmfWriter::Ranks>& frame_ranks = r.frame_ranks;
  if (frame_ranks) r.ranks.sum(0L);  // the other ranks wait until rank 0 has prepared the directory
  // Every rank: each computes its own cells' (cell_centroids.h).
  const std::vector<Eigen::Vector3d> centroids = r.branch_centroids();
  if (root) {
    r.output.emplace(c, r.scenario, r.resume, frame_ranks, centroids);
  } else if (frame_ranks && c.output.xdmf) {
    r.other_frames.emplace(c.output.dir, r.resume, "rbcflow", frame_ranks);
  }
}

Run::~Run() = default;

long Run::first_step() const { return state_->first; }
long Run::last_step() const { return state_->last; }
const CellStepper& Run::stepper() const { return *state_->stepper; }
const Scenario& Run::scenario() const { return state_->scenario; }
const Case& Run::c() const { return state_->request.c; }

void Run::step() {
  State& r = *state_;
  r.guarded([&] {
    const Case& c = r.request.c;
    CellStepper& stepper = *r.stepper;
    const long n = stepper.steps();
    const int threads = r.request.threads_handed_over ? r.request.threads_handed_over() : 0;
    if (threads > 0 && threads != omp_get_max_threads()) {
      omp_set_num_threads(threads);
      if (!r.request.quiet && r.ranks.root()) std::printf("threads: %d from step %ld on (handed over by the study)\n", threads, n);
    }
    const auto t0 = Clock::now();
    FlowSolution s = stepper.solve();
    r.ranks.check_same(s.gmres_cells, "the cells' GMRES iterations");
    r.ranks.check_same(s.gmres_wall, "the wall's GMRES iterations");
    const bool resumed_here = r.resume && n == *r.resume;  // the run before the restart wrote step n
    const bool frame_now = n % c.output.every == 0 && !resumed_here;
    const bool render_now = c.output.render && c.output.render_every > 0 && n % c.output.render_every == 0 && !resumed_here;
    if (frame_now || render_now) r.output_state(stepper, s, frame_now, render_now);
    const StepReport report = stepper.advance(s);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const std::vector<Eigen::Vector3d> centroids = r.branch_centroids();
    if (r.output) {
      r.output->diagnostics().write(diagnostics_row(stepper, report, r.scenario, seconds));
      r.output->branches(stepper, report, centroids);
    }
    if (report.max_volume_error > kMaxVolumeError) {
      char what[160];
      std::snprintf(what, sizeof what, "a cell's volume changed by %.3g%% at step %ld", 100 * report.max_volume_error,
                    stepper.steps());
      throw std::runtime_error(std::string(what).append(" (more than 1%: the run is unstable; try a smaller dt or "
                                                        "more de-aliasing)"));
    }
    if (c.output.checkpoint_every > 0 && stepper.steps() % c.output.checkpoint_every == 0) {
      r.last_checkpoint = checkpoint_path(c.output.dir, stepper.steps());
      write_checkpoint(stepper, c, *r.last_checkpoint, r.ranks);  // every rank: written together
    }
    r.progress->update(stepper.steps(), stepper.time(), seconds);
  });
}

void Run::finish() {
  State& r = *state_;
  r.guarded([&] {
    // The final state: its frame and render (the steps wrote the states before it; a restart
    // that took no step is at the state the earlier run wrote), and its checkpoint when not
    // already written.
    const Case& c = r.request.c;
    CellStepper& stepper = *r.stepper;
    const long n = stepper.steps();
    if (!(r.resume && n == *r.resume)) {
      const FlowSolution s = stepper.solve();  // on every rank: its products are shared
      r.output_state(stepper, s, true, c.output.render);
    }
    const int every = c.output.checkpoint_every;
    if (every > 0 && n % every != 0) {
      r.last_checkpoint = checkpoint_path(c.output.dir, n);
      write_checkpoint(stepper, c, *r.last_checkpoint, r.ranks);  // every rank: written together
    }
    if (r.output && c.output.render) {
      plot_diagnostics(c.output.dir / "diagnostics.csv", c.output.dir / "diagnostics.png");
    }
  });
}

void Run::checkpoint(const fs::path& file) {
  write_checkpoint(*state_->stepper, state_->request.c, file, state_->ranks);
  state_->last_checkpoint = file;
}

void check_run_directory(const RunRequest& request, const std::string& overwrite_option,
                         const std::string& restart_option) {
  const fs::path& dir = request.c.output.dir;
  if (request.overwrite) return;
  const std::vector<std::string> found = run_files(dir);
  if (found.empty() || (!request.restart.empty() && restarts_in_place(request.restart, dir))) return;
  std::string list;
  for (const std::string& f : found) list.append(list.empty() ? "" : ", ").append(f);
  throw case_error(request.c, "output.dir",
                   "the output directory " + dir.string() + " holds an earlier run (" + list + "); pass " +
                       overwrite_option + " to replace it, " + restart_option + " " + (dir / "checkpoints").string() +
                       "/step_N.h5 to continue it, or write elsewhere");
}

void run_case(const RunRequest& request) {
  Run run(request);
  while (!run.done()) run.step();
  run.finish();
  if (!request.quiet && Communicator::world().root()) {
    std::printf("done: %ld steps, t = %.5g, output in %s\n", run.last_step() - run.first_step(), run.stepper().time(),
                request.c.output.dir.c_str());
  }
}

}  // namespace rbcflow
