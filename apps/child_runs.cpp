#include "child_runs.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <map>
#include <stdexcept>

#include "self_executable.h"

extern char** environ;

namespace rbcflow::cli {
namespace {

using Clock = std::chrono::steady_clock;

// This process's environment with OMP_NUM_THREADS replaced: built before fork, because a child
// of a multithreaded process may only make async-signal-safe calls until it execs.
std::vector<std::string> child_environment(int threads) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    if (std::strncmp(*e, "OMP_NUM_THREADS=", 16) != 0) env.emplace_back(*e);
  }
  env.push_back("OMP_NUM_THREADS=" + std::to_string(threads));
  return env;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (std::string& s : strings) p.push_back(s.data());
  p.push_back(nullptr);
  return p;
}

// Starts one child with stdout and stderr in `log`; returns its pid, or -1.
pid_t start(const std::string& exe, const ChildRun& run, std::vector<std::string>& env) {
  const int log = ::open(run.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) return -1;
  std::vector<std::string> argv = {exe};
  argv.insert(argv.end(), run.args.begin(), run.args.end());
  std::vector<char*> argp = pointers(argv), envp = pointers(env);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::execve(exe.c_str(), argp.data(), envp.data());
    const char message[] = "rbcflow: cannot start the child process\n";
    [[maybe_unused]] const ssize_t w = ::write(STDERR_FILENO, message, sizeof message - 1);
    ::_exit(127);
  }
  ::close(log);
  return pid;
}

int exit_status(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 127;
}

}  // namespace

std::vector<ChildResult> run_children(const std::vector<ChildRun>& runs, int jobs, int threads,
                                      const std::function<void(std::size_t)>& on_start,
                                      const std::function<void(std::size_t, const ChildResult&)>& on_done) {
  if (jobs < 1 || threads < 1) throw std::invalid_argument("run_children: jobs and threads must be positive");
  const std::string exe = self_executable();
  if (exe.empty()) throw std::runtime_error("cannot find this executable (/proc/self/exe) to run the cases");
  std::vector<std::string> env = child_environment(threads);
  std::vector<ChildResult> results(runs.size());
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  std::size_t next = 0;
  while (next < runs.size() || !running.empty()) {
    while (next < runs.size() && static_cast<int>(running.size()) < jobs) {
      const std::size_t k = next++;
      on_start(k);
      const pid_t pid = start(exe, runs[k], env);
      if (pid > 0) {
        running[pid] = {k, Clock::now()};
      } else {
        results[k].exit_status = 127;
        on_done(k, results[k]);
      }
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("waiting for the case runs: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not one of ours
    const auto [k, started] = it->second;
    running.erase(it);
    results[k].exit_status = exit_status(status);
    results[k].seconds = std::chrono::duration<double>(Clock::now() - started).count();
    on_done(k, results[k]);
  }
  return results;
}

}  // namespace rbcflow::cli
