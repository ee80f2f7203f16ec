#pragma once
// A run: from a case's initial state or a checkpoint to time.end, writing the output directory
// (docs/case-format.md): what `rbcflow run` does, and `rbcflow study` for each case. Solve the
// flow at X^n, write what is due at step n (frame, cells.csv, render), advance, write the
// diagnostics row and any checkpoint.
#include <filesystem>
#include <functional>

#include "io/case.h"

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

// Throws CaseError / CheckpointError (exit 2) for a case or checkpoint that cannot be run, and
// std::runtime_error (exit 1) naming the step and the last good checkpoint when the run fails.
// Renders need an X display: the caller provides one first when c.output.render is on.
void run_case(const RunRequest& request);

}  // namespace rbcflow
