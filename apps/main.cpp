// rbcflow: red blood cells in Stokes flow by the spectral boundary integral method.
// Thin: parse the command, call the library, report. Errors are caught here, once.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli.h"
#include "io/input_error.h"
#include "libsolver/stepper/step_memory.h"

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

}  // namespace

int main(int argc, char** argv) {
  using namespace rbcflow::cli;
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    print_usage();
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  rbcflow::reuse_freed_memory();  // time steps reuse the pages of the steps before
  Args args(command, std::vector<std::string>(argv + 2, argv + argc));
  try {
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
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const rbcflow::InputError& e) {
    std::fprintf(stderr, "rbcflow %s: %s\n", command.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rbcflow %s: error: %s\n", command.c_str(), e.what());
    return 1;
  }
}
