// rbcflow info: version, the libraries found, the OpenMP thread count and the MPI ranks.
#include <CGAL/version.h>
#include <H5public.h>
#include <fftw3.h>
#include <gmsh.h>
#include <omp.h>
#include <vtkVersion.h>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <cstdio>
#include <toml.hpp>

#include "cli.h"
#include "io/checkpoint.h"
#include "libsolver/parallel/communicator.h"
#include "libsolver/parallel/slab_fft.h"
#include "rbcflow_version.h"

namespace rbcflow::cli {
namespace {

std::string gmsh_version() {
  // gmsh::initialize() resets the OpenMP thread count to 1 (gmsh 4.8 calls omp_set_num_threads): restore it.
  const int threads = omp_get_max_threads();
  gmsh::initialize(0, nullptr, false);
  std::string v;
  gmsh::option::getString("General.Version", v);
  gmsh::finalize();
  omp_set_num_threads(threads);
  return v;
}

}  // namespace

int run_info(Args& args) {
  if (args.help_requested()) {
    std::printf("usage: rbcflow info\n  Prints the version, the libraries found, the OpenMP thread count and the MPI ranks.\n");
    return 0;
  }
  args.finish();
  unsigned h5maj = 0, h5min = 0, h5rel = 0;
  H5get_libversion(&h5maj, &h5min, &h5rel);
  std::printf("rbcflow %s\n", RBCFLOW_VERSION);
  std::printf("  method: Zhao, Isfahani, Olson & Freund, J. Comput. Phys. 229 (2010) 3726-3744\n");
  std::printf("libraries:\n");
  std::printf("  Eigen    %d.%d.%d\n", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION);
  std::printf("  FFTW     %s\n", fftw_version);
  std::printf("  gmsh     %s\n", gmsh_version().c_str());
  std::printf("  VTK      %s\n", vtkVersion::GetVTKVersion());
  std::printf("  CGAL     %s\n", CGAL_VERSION_STR);
  std::printf("  HDF5     %u.%u.%u%s\n", h5maj, h5min, h5rel,
              CheckpointWriter::shared_by_ranks() ? " (parallel: the ranks write rbcflow.h5 and the checkpoints together)" : "");
  std::printf("  toml11   %d.%d.%d\n", TOML11_VERSION_MAJOR, TOML11_VERSION_MINOR, TOML11_VERSION_PATCH);
  std::printf("  Boost    %d.%d.%d\n", BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000, BOOST_VERSION % 100);
  std::printf("  OpenMP   %d (spec date)\n", _OPENMP);
  if (built_with_mpi()) {
    std::printf("  MPI      %s\n", mpi_library_version().c_str());
    std::printf("  FFTW MPI %s\n", SlabFft::available() ? "yes: the Ewald grids are split in slabs over the ranks"
                                                         : "no (libfftw3-mpi-dev): every rank transforms whole Ewald grids");
  }
  std::printf("threads:   %d (OpenMP; set OMP_NUM_THREADS to change)\n", omp_get_max_threads());
  const Communicator ranks = Communicator::world();
  std::printf("parallel:  %s%s\n", ranks_and_threads(ranks.size(), omp_get_max_threads()).c_str(),
              built_with_mpi() ? " (mpirun -np P rbcflow run CASE.toml: P ranks)" : " (built without MPI: one rank)");
  return 0;
}

}  // namespace rbcflow::cli
