// rbcflow: red blood cells in Stokes flow by the spectral boundary integral method.
// Thin: parse the command, call the library, report. Errors are caught here, once.
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "cli.h"
#include "io/input_error.h"
#include "libsolver/parallel/communicator.h"

namespace {

void print_usage() {
  std::printf(
      "usage: rbcflow COMMAND [ARGS]\n"
      "commands:\n"
      "  run CASE.toml        run a case (ParaView output, diagnostics, checkpoints)\n"
      "  study CASE.toml... -o DIR  run a tube study; mu_eff against D with the Pries law\n"
      "  check CASE.toml      validate a case; print derived parameters\n"
      "  mesh CASE.toml -o W.msh  mesh the vessel; write W.msh and W.vtp\n"
      "  render OUTDIR -o F.png  render a saved frame (or --plot the diagnostics)\n"
      "  info                 version, libraries, threads\n"
      "  shape NAME -o F.vtp  export a reference cell shape (rbc, sphere, ellipsoid, ...)\n"
      "Run 'rbcflow COMMAND --help' for the arguments of a command.\n");
}

// Reports a failure and returns its exit status. Under mpirun rank 0 reports as a single process
// does and another rank names itself, except for bad input, which every rank read alike; one
// rank's failure ends them all (the others would wait for it). A failure of the replicated
// state happens on every rank at once: the other ranks wait 2 s before ending the run, so that
// rank 0's message is written before MPI_Abort stops it.
int fail(const std::string& command, const char* kind, const char* what, int status, bool every_rank) {
  const rbcflow::Communicator ranks = rbcflow::Communicator::world();
  if (ranks.root()) {
    std::fprintf(stderr, "rbcflow %s: %s%s\n", command.c_str(), kind, what);
  } else if (every_rank) {
    std::fprintf(stderr, "rbcflow %s (rank %d): %s%s\n", command.c_str(), ranks.rank(), kind, what);
  }
  std::fflush(stderr);
  if (!ranks.root()) std::this_thread::sleep_for(std::chrono::seconds(2));
  rbcflow::MpiSession::abort_all(status);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rbcflow::cli;
  rbcflow::MpiSession mpi(argc, argv);  // only when started by mpirun
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    print_usage();
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  Args args(command, std::vector<std::string>(argv + 2, argv + argc));
  try {
    if (rbcflow::Communicator::world().size() > 1 && command != "run" && command != "info")
      throw UsageError("rbcflow " + command + ": runs as one process; of the commands only run (and info) take mpirun -np P");
    if (command == "run") return run_run(args);
    if (command == "info") return run_info(args);
    if (command == "shape") return run_shape(args);
    if (command == "check") return run_check(args);
    if (command == "mesh") return run_mesh(args);
    if (command == "render") return run_render(args);
    if (command == "study") return run_study(args);
    std::fprintf(stderr, "rbcflow: unknown command '%s'\n", command.c_str());
    print_usage();
    return 2;
  } catch (const UsageError& e) {
    if (rbcflow::Communicator::world().root()) std::fprintf(stderr, "%s\n", e.what());
    rbcflow::MpiSession::abort_all(2);
    return 2;
  } catch (const rbcflow::InputError& e) {
    return fail(command, "", e.what(), 2, false);
  } catch (const std::exception& e) {
    return fail(command, "error: ", e.what(), 1, true);
  }
}
