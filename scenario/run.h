#pragma once
// A run: from a case's initial state or a checkpoint to time.end, writing the output directory
// (docs/case-format.md): what `rbcflow run` does, `rbcflow study` for each case, and the Python
// module's Simulation step by step. A step solves the flow at X^n, writes what is due at step n
// (frame, cells.csv, render), advances, and writes the diagnostics row and any checkpoint.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "io/case.h"
#include "libsolver/stepper/cell_stepper.h"
#include "scenario/scenario.h"

namespace rbcflow {

struct RunRequest {
  Case c;                         // output.dir as it will be used
  std::filesystem::path restart;  // a checkpoint of this case, or empty
  long steps = 0;                 // steps to run; 0: to time.end
  bool quiet = false;
  bool overwrite = false;  // clear an earlier run's files from output.dir first (the caller checks)
  // Between steps: a new OpenMP thread count handed over by whoever started the run, or 0.
  std::function<int()> threads_handed_over;
};

// Renders need an X display: the caller provides one first when c.output.render is on.
class Run {
 public:
  // Prepares the scenario, makes the stepper, restores the checkpoint, clears an earlier run
  // (request.overwrite), opens the output and writes case.toml. Throws CaseError /
  // CheckpointError (exit 2) for a case or checkpoint that cannot be run; writes nothing then.
  explicit Run(RunRequest request);
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  long first_step() const;
  long last_step() const;  // time.end's step, or first_step() + request.steps
  bool done() const { return stepper().steps() >= last_step(); }
  // One step with its output. Throws std::runtime_error (exit 1) naming the step and the last
  // good checkpoint when it fails (a cell losing 1% of its volume, GMRES not converging).
  void step();
  // The final state's frame and render, its checkpoint (when checkpoints are on and it has none
  // yet) and the diagnostics plot. Call once, when the stepping is over.
  void finish();
  // A checkpoint of the current state (it becomes the last good one).
  void checkpoint(const std::filesystem::path& file);

  const CellStepper& stepper() const;
  const Scenario& scenario() const;
  const Case& c() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// A directory that holds another run's files is not written into by accident: only with
// request.overwrite (which clears them first) or to continue that very run from one of its
// checkpoints. Throws CaseError naming output.dir, the directory, its run's files and the two
// options by the names the caller gives them (the command line's flags, Python's arguments).
void check_run_directory(const RunRequest& request, const std::string& overwrite_option,
                         const std::string& restart_option);

// A whole run: Run, step() until done(), finish(), with a progress line and a closing summary
// unless quiet.
void run_case(const RunRequest& request);

}  // namespace rbcflow
