#pragma once
// Threads handed over to running cases: `rbcflow study --jobs J` starts each case run with its
// share of the threads; once no case is left to start, the runs still going get the threads of
// those that ended, so that the last run of a sweep does not leave cores idle. The study writes
// each new count as a line of text to a pipe whose read end the run finds at the descriptor
// named by RBCFLOW_THREADS_FD; the run reads it between steps.
namespace rbcflow::cli {

inline constexpr const char* kThreadsFdVariable = "RBCFLOW_THREADS_FD";
inline constexpr int kThreadsFd = 3;  // where a child run finds the read end

// The run's side: the last thread count written since the previous call, or 0 (none written,
// or this run was not started by a study).
int threads_handed_over();

}  // namespace rbcflow::cli
