#include "child_runs.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <map>
#include <stdexcept>

#include "self_executable.h"
#include "thread_handover.h"

extern char** environ;

namespace rbcflow::cli {
namespace {

using Clock = std::chrono::steady_clock;

// This process's environment with OMP_NUM_THREADS replaced and the thread handover's
// descriptor named: built before fork, because a child of a multithreaded process may only
// make async-signal-safe calls until it execs.
std::vector<std::string> child_environment(int threads) {
  const std::string handover = std::string(kThreadsFdVariable) + "=";
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string variable = *e;
    if (!variable.starts_with("OMP_NUM_THREADS=") && !variable.starts_with(handover)) env.push_back(variable);
  }
  env.push_back("OMP_NUM_THREADS=" + std::to_string(threads));
  env.push_back(handover + std::to_string(kThreadsFd));
  return env;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (std::string& s : strings) p.push_back(s.data());
  p.push_back(nullptr);
  return p;
}

struct Running {
  std::size_t index;
  Clock::time_point started;
  int handover;  // write end of the child's thread handover pipe
  int threads;
};

// Starts one child with stdout and stderr in `log` and the read end of a new pipe at kThreadsFd;
// returns its pid (and the pipe's write end in `handover`), or -1.
pid_t start(const std::string& exe, const ChildRun& run, std::vector<std::string>& env, int& handover) {
  int pipe_ends[2];
  if (::pipe2(pipe_ends, O_CLOEXEC) != 0) return -1;
  const int log = ::open(run.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) {
    ::close(pipe_ends[0]);
    ::close(pipe_ends[1]);
    return -1;
  }
  std::vector<std::string> argv = {exe};
  argv.insert(argv.end(), run.args.begin(), run.args.end());
  std::vector<char*> argp = pointers(argv), envp = pointers(env);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl
    ::signal(SIGPIPE, SIG_DFL);  // ignored in this process while it writes to the pipes
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    if (pipe_ends[0] == kThreadsFd) {
      ::fcntl(kThreadsFd, F_SETFD, 0);  // keep it open across exec
    } else {
      ::dup2(pipe_ends[0], kThreadsFd);
    }
    ::execve(exe.c_str(), argp.data(), envp.data());
    const char message[] = "rbcflow: cannot start the child process\n";
    [[maybe_unused]] const ssize_t w = ::write(STDERR_FILENO, message, sizeof message - 1);
    ::_exit(127);
  }
  ::close(log);
  ::close(pipe_ends[0]);
  if (pid > 0) {
    handover = pipe_ends[1];
  } else {
    ::close(pipe_ends[1]);
  }
  return pid;
}

int exit_status(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 127;
}

// Once every run has started, the ones still going share all the threads, those started first
// taking the remainder; a child only ever gains threads.
void hand_over(std::map<pid_t, Running>& running, int threads) {
  std::vector<Running*> order;
  for (auto& entry : running) order.push_back(&entry.second);
  std::sort(order.begin(), order.end(), [](const Running* a, const Running* b) { return a->index < b->index; });
  const int n = static_cast<int>(order.size());
  for (int i = 0; i < n; ++i) {
    Running& r = *order[i];
    const int share = threads / n + (i < threads % n ? 1 : 0);
    if (share <= r.threads) continue;
    const std::string line = std::to_string(share) + "\n";
    if (::write(r.handover, line.data(), line.size()) == static_cast<ssize_t>(line.size())) r.threads = share;
  }
}

// SIGPIPE ignored while it lives: writing to the pipe of a child that has ended fails instead.
struct IgnoredSigpipe {
  struct sigaction previous {};
  IgnoredSigpipe() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    ::sigaction(SIGPIPE, &ignore, &previous);
  }
  ~IgnoredSigpipe() { ::sigaction(SIGPIPE, &previous, nullptr); }
  IgnoredSigpipe(const IgnoredSigpipe&) = delete;
  IgnoredSigpipe& operator=(const IgnoredSigpipe&) = delete;
};

}  // namespace

int initial_threads(int jobs, std::size_t runs, int threads) {
  const int slots = static_cast<int>(std::min<std::size_t>(std::max(jobs, 1), std::max<std::size_t>(runs, 1)));
  return std::max(1, threads / slots);
}

std::vector<ChildResult> run_children(const std::vector<ChildRun>& runs, int jobs, int threads,
                                      const std::function<void(std::size_t)>& on_start,
                                      const std::function<void(std::size_t, const ChildResult&)>& on_done) {
  if (jobs < 1 || threads < 1) throw std::invalid_argument("run_children: jobs and threads must be positive");
  const std::string exe = self_executable();
  if (exe.empty()) throw std::runtime_error("cannot find this executable (/proc/self/exe) to run the cases");
  const int each = initial_threads(jobs, runs.size(), threads);
  std::vector<std::string> env = child_environment(each);
  const IgnoredSigpipe ignored;  // a handover written to a child that has just ended
  std::vector<ChildResult> results(runs.size());
  std::map<pid_t, Running> running;
  std::size_t next = 0;
  while (next < runs.size() || !running.empty()) {
    while (next < runs.size() && static_cast<int>(running.size()) < jobs) {
      const std::size_t k = next++;
      on_start(k);
      int handover = -1;
      const pid_t pid = start(exe, runs[k], env, handover);
      if (pid > 0) {
        running[pid] = {k, Clock::now(), handover, each};
      } else {
        results[k].exit_status = 127;
        on_done(k, results[k]);
      }
    }
    if (running.empty()) continue;
    if (next == runs.size()) hand_over(running, threads);
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("waiting for the case runs: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not one of ours
    const Running ended = it->second;
    running.erase(it);
    ::close(ended.handover);
    results[ended.index].exit_status = exit_status(status);
    results[ended.index].seconds = std::chrono::duration<double>(Clock::now() - ended.started).count();
    on_done(ended.index, results[ended.index]);
  }
  return results;
}

}  // namespace rbcflow::cli
