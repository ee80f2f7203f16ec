# Finds every package of the stack from Debian 12 packages (Eigen 3.4, FFTW 3.3, gmsh 4.8,
# VTK 9.1, CGAL 5.5, serial HDF5 1.10, GoogleTest, toml11 3.7, OpenMP), and OpenMPI for distributed
# runs when installed (with FFTW's MPI library and HDF5's OpenMPI build, which then replaces the
# serial one).
# A missing package stops configuration with the name of the Debian package to install;
# scripts/install-deps.sh installs all of them.

macro(rbcflow_require found_var debian_package what)
  if(NOT ${found_var})
    message(FATAL_ERROR
      "rbcflow: ${what} not found. Install the Debian package '${debian_package}' "
      "(apt-get install ${debian_package}), or run scripts/install-deps.sh as root.")
  endif()
endmacro()

find_package(Eigen3 3.3 QUIET NO_MODULE)
rbcflow_require(Eigen3_FOUND libeigen3-dev "Eigen 3")

find_package(PkgConfig QUIET)
rbcflow_require(PKG_CONFIG_FOUND pkg-config "pkg-config")
pkg_check_modules(FFTW3 QUIET IMPORTED_TARGET fftw3)   # Debian ships no FFTW3Config.cmake
rbcflow_require(FFTW3_FOUND libfftw3-dev "FFTW 3")
find_library(FFTW3_OMP_LIBRARY fftw3_omp)
rbcflow_require(FFTW3_OMP_LIBRARY libfftw3-dev "FFTW 3 OpenMP library (fftw3_omp)")

find_path(GMSH_INCLUDE_DIR gmsh.h)                      # gmsh has no cmake or pc file
find_library(GMSH_LIBRARY gmsh)
rbcflow_require(GMSH_INCLUDE_DIR libgmsh-dev "gmsh C++ API header gmsh.h")
rbcflow_require(GMSH_LIBRARY libgmsh-dev "gmsh library")
if(NOT TARGET rbcflow::gmsh)
  add_library(rbcflow::gmsh INTERFACE IMPORTED)
  target_include_directories(rbcflow::gmsh INTERFACE ${GMSH_INCLUDE_DIR})
  target_link_libraries(rbcflow::gmsh INTERFACE ${GMSH_LIBRARY})
endif()
file(STRINGS ${GMSH_INCLUDE_DIR}/gmsh.h _gmsh_version_line REGEX "define GMSH_API_VERSION \"")
string(REGEX MATCH "[0-9.]+" GMSH_VERSION "${_gmsh_version_line}")

# RenderingAnnotation: colour bars; Charts/Context: the diagnostics plot (io/plot.cpp).
find_package(VTK 9.1 QUIET COMPONENTS CommonCore CommonDataModel FiltersCore FiltersSources
  IOXML IOImage IOGeometry RenderingCore RenderingOpenGL2 RenderingFreeType InteractionStyle
  RenderingAnnotation ChartsCore ViewsContext2D RenderingContext2D RenderingContextOpenGL2)
rbcflow_require(VTK_FOUND libvtk9-dev "VTK 9")

find_package(CGAL 5.5 QUIET)
rbcflow_require(CGAL_FOUND libcgal-dev "CGAL 5.5")

set(HDF5_PREFER_PARALLEL OFF)          # pkg-config hdf5 points at the OpenMPI build
find_package(HDF5 QUIET COMPONENTS C CXX)
rbcflow_require(HDF5_FOUND libhdf5-dev "HDF5 (serial, C and C++)")

find_package(OpenMP QUIET)
rbcflow_require(OpenMP_CXX_FOUND "g++ (libgomp)" "OpenMP for C++")

# Distributed runs (libsolver/parallel): OpenMPI when installed; without it the build runs on
# one rank. RBCFLOW_MPI=OFF builds without it even where it is installed.
option(RBCFLOW_MPI "Build for distributed runs with MPI (mpirun -np P rbcflow run)" ON)
set(RBCFLOW_WITH_MPI OFF)
set(RBCFLOW_WITH_FFTW_MPI OFF)
set(RBCFLOW_WITH_PARALLEL_HDF5 OFF)
if(RBCFLOW_MPI)
  find_package(MPI QUIET COMPONENTS CXX)
  if(MPI_CXX_FOUND)
    set(RBCFLOW_WITH_MPI ON)
    # The Ewald grids split in slabs over the ranks (libsolver/parallel/slab_fft.h); without
    # FFTW's MPI library every rank transforms the whole grid.
    find_library(FFTW3_MPI_LIBRARY fftw3_mpi)
    find_path(FFTW3_MPI_INCLUDE_DIR fftw3-mpi.h)
    if(FFTW3_MPI_LIBRARY AND FFTW3_MPI_INCLUDE_DIR)
      set(RBCFLOW_WITH_FFTW_MPI ON)
    else()
      message(STATUS "rbcflow: FFTW's MPI library not found (Debian: libfftw3-mpi-dev): every rank transforms the whole Ewald grid")
    endif()
    # Checkpoints written by the ranks together (io/hdf5_file.h): HDF5's OpenMPI build, linked in
    # place of the serial one (one HDF5 per process: no other library rbcflow loads needs HDF5).
    pkg_check_modules(HDF5_OPENMPI QUIET IMPORTED_TARGET hdf5-openmpi)
    if(HDF5_OPENMPI_FOUND)
      set(RBCFLOW_WITH_PARALLEL_HDF5 ON)
    else()
      message(STATUS "rbcflow: parallel HDF5 not found (Debian: libhdf5-openmpi-dev): rank 0 writes the checkpoints")
    endif()
  else()
    message(STATUS "rbcflow: MPI not found (Debian: libopenmpi-dev openmpi-bin): building for one rank")
  endif()
endif()

# The HDF5 that io/ and everything reading its files link: one per process.
add_library(rbcflow_hdf5 INTERFACE)
if(RBCFLOW_WITH_PARALLEL_HDF5)
  target_link_libraries(rbcflow_hdf5 INTERFACE PkgConfig::HDF5_OPENMPI MPI::MPI_CXX)
else()
  target_link_libraries(rbcflow_hdf5 INTERFACE HDF5::HDF5)
endif()

find_package(toml11 QUIET)
rbcflow_require(toml11_FOUND libtoml11-dev "toml11")

find_package(Boost 1.74 QUIET)         # header-only Boost.Math (reference values in tests)
rbcflow_require(Boost_FOUND libboost-dev "Boost headers")

if(RBCFLOW_BUILD_TESTS)
  find_package(GTest QUIET)
  rbcflow_require(GTest_FOUND libgtest-dev "GoogleTest")
  include(GoogleTest)
endif()
if(RBCFLOW_BUILD_BENCH)
  find_package(benchmark QUIET)
  rbcflow_require(benchmark_FOUND libbenchmark-dev "Google Benchmark")
endif()
