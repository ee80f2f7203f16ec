#pragma once
// The run loop of `rbcflow run` (and of each case of `rbcflow study`): from a case's initial
// state or a checkpoint to time.end, writing the output directory of CASE_FORMAT.md. Solve the
// flow at X^n, write what is due at step n (frame, cells.csv, render), advance, write the
// diagnostics row and any checkpoint.
#include <filesystem>

#include "io/case.h"

namespace rbcflow::cli {

struct RunRequest {
  Case c;                         // output.dir as it will be used
  std::filesystem::path restart;  // a checkpoint of this case, or empty
  long steps = 0;                 // steps to run; 0: to time.end
  bool quiet = false;
};

// Throws CaseError / CheckpointError (exit 2) for a case or checkpoint that cannot be run, and
// std::runtime_error (exit 1) naming the step and the last good checkpoint when the run fails.
// Renders need a display: the caller calls ensure_display() first when c.output.render is on.
void run_case(const RunRequest& request);

}  // namespace rbcflow::cli
