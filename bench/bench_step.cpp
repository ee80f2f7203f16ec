// Seconds per time step of the coupled solver with the split of issue 9 (membrane force,
// corrections build, GMRES products, wall solve), for the cases of bench/step_cases.h:
//   build/bin/bench_step minicase [--steps 5]
//   OMP_NUM_THREADS=1 build/bin/bench_step tube27 --steps 2
//   build/bin/bench_step wide125 --steps 3 --memory-gib 2.6   (the case's solver.memory_gib)
// One line per step (step 1 of a lambda != 1 case with walls includes the start sweeps), then
// the minimum over the later steps of each column (wall-clock seconds; cpu: process CPU time,
// all threads; sys: the part of it in the kernel; faults: thousands of minor page faults, the
// pages a step maps afresh: a run that returns its freed memory to the system faults its
// workspaces in again at each step, scenario/memory_budget.h). Set-up (mesh, wall operator and its LU,
// placement) is timed apart; what the last step's operators held (by structure, per cell) and
// the peak resident memory of the process close the output.
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "libsolver/parallel/communicator.h"
#include "step_cases.h"

using namespace rbcflow;

namespace {

struct Column {
  const char* name;
  double StepTimings::*field;
};

constexpr Column kColumns[] = {
    {"membrane", &StepTimings::membrane},
    {"geometry", &StepTimings::cell_geometry},
    {"self", &StepTimings::self_corrections},
    {"near", &StepTimings::near_corrections},
    {"at_wall", &StepTimings::at_wall_build},
    {"wall_op", &StepTimings::wall_at_cells_build},
    {"cell_prod", &StepTimings::cell_products},
    {"prod_corr", &StepTimings::cell_corrections},
    {"dl_real", &StepTimings::cell_ewald_real},
    {"dl_spread", &StepTimings::cell_ewald_spreading},
    {"dl_fft", &StepTimings::cell_ewald_fft},
    {"dl_interp", &StepTimings::cell_ewald_interpolation},
    {"wall_prod", &StepTimings::at_wall_products},
    {"wall_solve", &StepTimings::wall_solve},
    {"wall_vel", &StepTimings::wall_at_cells},
};

rusage process_usage() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage;
}

double peak_resident_mb() { return process_usage().ru_maxrss / 1024.0; }  // Linux: kilobytes

double seconds(const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); }

// What the kernel did for the process between two samples.
struct KernelShare {
  double sys = 0;     // seconds of system time, all threads
  double faults = 0;  // minor page faults, thousands
};

KernelShare kernel_share(const rusage& from, const rusage& to) {
  return {seconds(to.ru_stime) - seconds(from.ru_stime), 1e-3 * static_cast<double>(to.ru_minflt - from.ru_minflt)};
}

void print_row(const char* label, double step, double cpu, const KernelShare& k, const StepTimings& t, int gmres_cells,
               int gmres_wall) {
  std::printf("%-6s %8.3f %8.3f %8.3f %8.0f", label, step, cpu, k.sys, k.faults);
  for (const Column& c : kColumns) std::printf(" %10.3f", t.*c.field);
  std::printf(" %6d %6d\n", gmres_cells, gmres_wall);
}

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);  // mpirun -np P bench_step CASE: the step on P ranks
  const Communicator ranks = Communicator::world();
  // Rank 0 prints the table; every other rank only its peak memory (on stderr), at the end.
  if (!ranks.root() && !std::freopen("/dev/null", "w", stdout)) return 1;
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_step single|minicase|tubeK|wideK [--steps K] [--memory-gib G]  (K cells in the D = 6 or D = 12 tube, e.g. tube27)\n");
    return 2;
  }
  const std::string name = argv[1];
  int steps = 5;
  double memory_gib = 0;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--steps") steps = std::max(1, std::atoi(argv[i + 1]));
    if (std::string(argv[i]) == "--memory-gib") {
      char* end = nullptr;
      memory_gib = std::strtod(argv[i + 1], &end);
      if (end == argv[i + 1] || *end != '\0' || !(memory_gib > 0)) {
        std::fprintf(stderr, "bench_step: --memory-gib takes a positive number of GiB, not '%s'\n", argv[i + 1]);
        return 2;
      }
    }
  }
  try {
    const auto t0 = std::chrono::steady_clock::now();
    bench::StepCase step_case = bench::make_step_case(name, memory_gib);
    auto& stepper = step_case.stepper;
    const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("case %s: %zu cells, %s, set-up %.2f s, peak memory after set-up %.0f MB\n", name.c_str(),
                stepper->cells().size(), ranks_and_threads(ranks.size(), omp_get_max_threads()).c_str(), setup,
                peak_resident_mb());
    std::printf("%-6s %8s %8s %8s %8s", "step", "total", "cpu", "sys", "faults");
    for (const Column& c : kColumns) std::printf(" %10s", c.name);
    std::printf(" %6s %6s\n", "it_c", "it_w");
    double best_step = 1e300, best_cpu = 1e300;
    KernelShare best_kernel{1e300, 1e300};
    MemoryReport memory;  // of the last step's operators
    long last_rows_received = 0, last_nodes = 0, last_wall_received = 0, last_traction_received = 0,
         last_velocity_received = 0;
    int last_iterations = 0, last_wall_iterations = 0, last_owned = 0, last_halo = 0;
    StepTimings best;
    for (const Column& c : kColumns) best.*c.field = 1e300;
    for (int k = 1; k <= steps; ++k) {
      const auto s0 = std::chrono::steady_clock::now();
      const std::clock_t c0 = std::clock();
      const rusage u0 = process_usage();
      const FlowSolution s = stepper->solve();
      const auto a0 = std::chrono::steady_clock::now();
      stepper->advance(s);
      const auto a1 = std::chrono::steady_clock::now();
      const double step = std::chrono::duration<double>(a1 - s0).count();
      const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      const KernelShare kernel = kernel_share(u0, process_usage());
      print_row(std::to_string(k).c_str(), step, cpu, kernel, s.timings, s.gmres_cells, s.gmres_wall);
      std::printf("       advance (the cells moved, collisions, volume, diagnostics): %.3f s\n",
                  std::chrono::duration<double>(a1 - a0).count());
      if (k <= 2) std::printf("       peak memory after step %d: %.0f MB\n", k, peak_resident_mb());
      memory = s.memory;
      last_rows_received = s.cell_rows_received;
      last_traction_received = s.traction_rows_received;
      last_velocity_received = s.velocity_rows_received;
      last_wall_received = s.wall_nodes_received;
      last_wall_iterations = s.gmres_wall;
      last_iterations = s.gmres_cells;
      if (!stepper->cells().empty())  // every cell's nodes
        last_nodes = static_cast<long>(stepper->cells().size()) * stepper->grids().n_grid->grid().size();
      last_owned = s.owned_cells;
      last_halo = s.halo_cells;
      std::fflush(stdout);
      if (k == 1 && steps > 1) continue;
      best_step = std::min(best_step, step);
      best_cpu = std::min(best_cpu, cpu);
      best_kernel = {std::min(best_kernel.sys, kernel.sys), std::min(best_kernel.faults, kernel.faults)};
      for (const Column& c : kColumns) best.*c.field = std::min(best.*c.field, s.timings.*c.field);
    }
    print_row("min", best_step, best_cpu, best_kernel, best, 0, 0);
    const double peak_mb = peak_resident_mb();
    const double cells = static_cast<double>(std::max<std::size_t>(1, stepper->cells().size()));
    std::printf("held by the last step's operators (MB per cell):\n");
    for (const MemoryReport::Item& i : memory.items())
      if (i.bytes > 0) std::printf("  %-52s %8.3f\n", i.name.c_str(), i.bytes / 1048576.0 / cells);
    std::printf("  %-52s %8.3f\n", "total", memory.total() / 1048576.0 / cells);
    std::printf("peak memory %.0f MB (%.1f MB per cell); rbcflow check's estimate %.0f MB\n", peak_mb, peak_mb / cells,
                step_case.estimated_peak_bytes / 1048576.0);
    if (!ranks.root()) std::fprintf(stderr, "rank %d: peak memory %.0f MB\n", ranks.rank(), peak_mb);
    if (ranks.size() > 1) {
      std::fprintf(stderr, "rank %d: %ld node rows received in the last step's products of (10), %d GMRES iterations, %ld cell nodes\n",
                   ranks.rank(), last_rows_received, last_iterations, last_nodes);
      std::fprintf(stderr, "rank %d: %d cells owned in the last step's products, a halo of %d of the other %d\n", ranks.rank(),
                   last_owned, last_halo, static_cast<int>(stepper->cells().size()) - last_owned);
      const long n_cells = std::max<long>(1, static_cast<long>(stepper->cells().size()));
      std::fprintf(stderr, "rank %d: %ld node rows of the traction received in the last step (all-gathered: %ld)\n",
                   ranks.rank(), last_traction_received, (n_cells - last_owned) * (last_nodes / n_cells));
      std::fprintf(stderr, "rank %d: %ld node rows of the velocity received in the last step (all-gathered: %ld)\n",
                   ranks.rank(), last_velocity_received, (n_cells - last_owned) * (last_nodes / n_cells));
      if (stepper->wall())
        std::fprintf(stderr, "rank %d: %ld wall nodes received in the last step's wall solves, %d GMRES iterations, %d wall nodes\n",
                     ranks.rank(), last_wall_received, last_wall_iterations, stepper->wall()->elements().num_nodes());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_step: %s\n", e.what());
    return 1;
  }
  return 0;
}
