#pragma once
// Commands of this executable run as child processes, a few at a time: the cases of a sweep
// side by side (two 1-thread runs keep two cores busier than one 2-thread run, whose serial
// parts leave a core idle). Each child writes its output to its own log file.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rbcflow::cli {

struct ChildRun {
  std::vector<std::string> args;  // after the executable, e.g. {"run", "case.toml", "--out", "dir"}
  std::filesystem::path log;      // the child's stdout and stderr
};

struct ChildResult {
  int exit_status = 0;  // the child's exit status; 128 + the signal that ended it
  double seconds = 0;
};

// The threads each child starts with: `threads` shared among min(jobs, runs) children, at least 1.
int initial_threads(int jobs, std::size_t runs, int threads);

// Runs every child, at most `jobs` at a time in the order given, each started with
// OMP_NUM_THREADS = initial_threads(jobs, runs.size(), threads); once every child has started,
// those still running share all `threads` (handed over between their steps, thread_handover.h).
// `on_start` and `on_done` are called with the run's index as each starts and ends.
// A child that cannot be started (its log not writable, no fork, no exec) ends with exit status
// 127. The children get SIGTERM if this process dies first.
std::vector<ChildResult> run_children(const std::vector<ChildRun>& runs, int jobs, int threads,
                                      const std::function<void(std::size_t)>& on_start,
                                      const std::function<void(std::size_t, const ChildResult&)>& on_done);

}  // namespace rbcflow::cli
