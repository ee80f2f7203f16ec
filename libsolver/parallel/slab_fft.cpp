#include "slab_fft.h"

#include <omp.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <string>

#include "geometry/sph/fftw_util.h"

#if defined(RBCFLOW_HAVE_MPI) && defined(RBCFLOW_HAVE_FFTW_MPI)
#include <fftw3-mpi.h>
#include <mpi.h>
#define RBCFLOW_SLAB_FFT 1
#endif

namespace rbcflow {

#ifdef RBCFLOW_SLAB_FFT

namespace {

void check_outside_parallel_region(const char* what) {
  if (omp_in_parallel())
    throw std::logic_error(std::string("slab FFT: ") + what + " inside an OpenMP parallel region (MPI is funnelled)");
}

}  // namespace

struct SlabFft::Plans {
  std::once_flag made_forward, made_forward1, made_backward;
  fftw_plan forward3 = nullptr, forward1 = nullptr, backward3 = nullptr;
  MPI_Comm comm = MPI_COMM_NULL;
  unsigned flags = FFTW_ESTIMATE;
  int threads = 1;
};

bool SlabFft::available() { return true; }

SlabFft::SlabFft(const Communicator& ranks, const std::array<int, 3>& size, unsigned flags, int threads)
    : size_(size), plans_(std::make_unique<Plans>()) {
  check_outside_parallel_region("set-up");
  {
    // FFTW's threads before its MPI interface (FFTW manual, section 6.11), once per process.
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    static const bool ready = fftw_init_threads() != 0 && (fftw_mpi_init(), true);
    (void)ready;
  }
  plans_->comm = MPI_Comm_f2c(ranks.mpi_handle());
  plans_->flags = flags;
  plans_->threads = threads;
  const ptrdiff_t n[3] = {size[0], size[1], size[2] / 2 + 1};  // the complex dimensions
  ptrdiff_t local_n0 = 0, local_0_start = 0, local_n1 = 0, local_1_start = 0;
  alloc3_ = static_cast<std::size_t>(fftw_mpi_local_size_many_transposed(
      3, n, 3, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, plans_->comm, &local_n0, &local_0_start, &local_n1,
      &local_1_start));
  ptrdiff_t n0 = 0, s0 = 0, n1 = 0, s1 = 0;
  alloc1_ = static_cast<std::size_t>(fftw_mpi_local_size_many_transposed(
      3, n, 1, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, plans_->comm, &n0, &s0, &n1, &s1));
  first_plane_ = static_cast<int>(local_0_start);
  planes_ = static_cast<int>(local_n0);
  first_row_ = static_cast<int>(local_1_start);
  rows_ = static_cast<int>(local_n1);
}

SlabFft::~SlabFft() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (finalised) return;  // a grid outliving MPI (a static cache): its plans go with the process
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  for (fftw_plan p : {plans_->forward3, plans_->forward1, plans_->backward3})
    if (p) fftw_destroy_plan(p);
}

std::size_t SlabFft::buffer_size(int components) const {
  const std::size_t n3 = size_[2] / 2 + 1;
  const std::size_t slab = static_cast<std::size_t>(planes_) * size_[1] * n3 * components;
  const std::size_t block = static_cast<std::size_t>(rows_) * size_[0] * n3 * components;
  return std::max({slab, block, components == 1 ? alloc1_ : alloc3_ / 3 * components});
}

namespace {

// Plans one transform in place on `data`, an array of the size FFTW asked for (planning
// overwrites it), or on an array of its own when `data` is null.
fftw_plan plan_slab(const std::array<int, 3>& size, int components, bool forward, MPI_Comm comm, unsigned flags,
                    int threads, std::size_t buffer_size, fftw_complex* data) {
  const ptrdiff_t n[3] = {size[0], size[1], size[2]};
  FftwBuffer<fftw_complex> own(data ? 0 : buffer_size);
  if (!data) data = own.data();
  double* real = reinterpret_cast<double*>(data);
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_plan_with_nthreads(threads);
  fftw_plan p = forward ? fftw_mpi_plan_many_dft_r2c(3, n, components, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK,
                                                     real, data, comm, flags | FFTW_MPI_TRANSPOSED_OUT)
                        : fftw_mpi_plan_many_dft_c2r(3, n, components, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK,
                                                     data, real, comm, flags | FFTW_MPI_TRANSPOSED_IN);
  fftw_plan_with_nthreads(1);  // other modules plan single-threaded FFTs
  if (!p) throw std::runtime_error("slab FFT: FFTW could not plan the distributed grid transform");
  return p;
}

void check_components(int components) {
  if (components != 3 && components != 1)
    throw std::invalid_argument("slab FFT: 3 or 1 interleaved grids, not " + std::to_string(components));
}

}  // namespace

void SlabFft::plan_forward(int components, fftw_complex* on) const {
  const bool three = components == 3;
  std::call_once(three ? plans_->made_forward : plans_->made_forward1, [&] {
    (three ? plans_->forward3 : plans_->forward1) = plan_slab(size_, components, true, plans_->comm, plans_->flags,
                                                              plans_->threads, buffer_size(components), on);
  });
}

void SlabFft::plan_backward(fftw_complex* on) const {
  std::call_once(plans_->made_backward, [&] {
    plans_->backward3 = plan_slab(size_, 3, false, plans_->comm, plans_->flags, plans_->threads, buffer_size(3), on);
  });
}

void SlabFft::plan_on(fftw_complex* data, int components) const {
  check_outside_parallel_region("planning a transform");
  check_components(components);
  plan_forward(components, data);
  if (components == 3) plan_backward(data);
}

void SlabFft::forward(fftw_complex* data, int components) const {
  check_outside_parallel_region("a transform");
  check_components(components);
  plan_forward(components, nullptr);
  fftw_mpi_execute_dft_r2c(components == 3 ? plans_->forward3 : plans_->forward1, reinterpret_cast<double*>(data), data);
}

void SlabFft::backward(fftw_complex* data) const {
  check_outside_parallel_region("a transform");
  plan_backward(nullptr);
  fftw_mpi_execute_dft_c2r(plans_->backward3, data, reinterpret_cast<double*>(data));
}

#else  // no FFTW MPI interface: SpmeGrid transforms whole grids

struct SlabFft::Plans {};

bool SlabFft::available() { return false; }

SlabFft::SlabFft(const Communicator&, const std::array<int, 3>& size, unsigned, int) : size_(size) {
  throw std::logic_error("slab FFT: this build has no FFTW MPI library (libfftw3-mpi-dev)");
}
SlabFft::~SlabFft() = default;
std::size_t SlabFft::buffer_size(int) const { return 0; }
void SlabFft::plan_forward(int, fftw_complex*) const {}
void SlabFft::plan_backward(fftw_complex*) const {}
void SlabFft::plan_on(fftw_complex*, int) const {}
void SlabFft::forward(fftw_complex*, int) const {}
void SlabFft::backward(fftw_complex*) const {}

#endif

}  // namespace rbcflow
