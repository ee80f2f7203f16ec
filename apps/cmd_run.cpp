// rbcflow run: parse the arguments, check the case and the output directory, run (scenario/run.h).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "cli.h"
#include "display.h"
#include "io/case.h"
#include "io/output_dir.h"
#include "libsolver/parallel/communicator.h"
#include "scenario/run.h"
#include "thread_handover.h"

namespace rbcflow::cli {
namespace {

namespace fs = std::filesystem;

void print_help() {
  std::printf(
      "usage: rbcflow run CASE.toml [--out DIR] [--restart CHECKPOINT.h5] [--steps N] [--overwrite] [--quiet]\n"
      "  Runs the case to time.end (or N more steps), writing to output.dir (or DIR):\n"
      "  case.toml, diagnostics.csv, cells.csv, rbcflow.xdmf/.h5, rbcflow.pvd + vtk/, renders/,\n"
      "  checkpoints/ and diagnostics.png. --restart continues from a checkpoint of the same case\n"
      "  exactly as the uninterrupted run would have, or with the cells' order (cells.order,\n"
      "  cells.dealias) or the time step (time.dt, time.dt_safety) changed: the shapes are then\n"
      "  resampled and the step history starts afresh. A directory that holds another run is\n"
      "  refused unless --overwrite (which first removes that run's files) or the restart\n"
      "  continues that run. Exit 0 on success, 2 for a bad case or\n"
      "  argument, 1 when the run fails (the message names the step and the last checkpoint).\n"
      "  mpirun -np P rbcflow run ... runs the same case on P ranks with the same output.\n");
}

}  // namespace

int run_run(Args& args) {
  if (args.help_requested()) {
    print_help();
    return 0;
  }
  std::string out, restart, steps_text;
  RunRequest request;
  request.quiet = args.flag("--quiet");
  request.overwrite = args.flag("--overwrite");
  args.option("--out", out);
  args.option("--restart", restart);
  args.option("--steps", steps_text);
  const fs::path case_file = args.positional("case file (CASE.toml)");
  args.finish();
  request.steps = steps_text.empty() ? 0 : positive_integer("run", "--steps", steps_text, std::numeric_limits<long>::max());  // 0: to time.end

  request.c = read_case(case_file);
  if (!out.empty()) request.c.output.dir = out;
  check_output_dir(request.c, request.c.output.dir);
  if (!restart.empty() && !fs::is_regular_file(restart)) {
    throw UsageError("rbcflow run: --restart " + restart + ": no such file");
  }
  request.restart = restart;
  request.threads_handed_over = threads_handed_over;  // from rbcflow study --jobs
  check_run_directory(request, "--overwrite", "--restart");
  if (request.c.output.render) {
    if (Communicator::world().size() > 1 && !std::getenv("DISPLAY")) {
      // The ranks cannot restart themselves under Xvfb (mpirun started them): no renders.
      request.c.output.render = false;
      if (Communicator::world().root())
        std::printf("renders: off, no X display on %d ranks (run mpirun under xvfb-run -a, or render the frames "
                    "afterwards with rbcflow render %s)\n", Communicator::world().size(), request.c.output.dir.c_str());
    } else {
      ensure_display();  // before any work: without a display the command restarts under Xvfb
    }
  }
  run_case(request);
  return 0;
}

}  // namespace rbcflow::cli
