#pragma once
// The 3-D real transforms of an Ewald grid split in slabs over the ranks of a run, by FFTW's MPI
// interface (FFTW manual, chapter 6 "Distributed-memory FFTW with MPI"). Rank r holds
//   - of the real grid, the planes [first_plane, first_plane + planes) of the first direction;
//   - of the spectrum, the rows [first_row, first_row + rows) of the second direction, transposed
//     (FFTW_MPI_TRANSPOSED_OUT: the forward transform leaves out its last global transpose and the
//     backward transform starts from the transposed spectrum).
// The transforms are in place. With K = (K1, K2, K3), n3 = K3/2 + 1, R = 2 n3 (FFTW's padding
// of the real rows) and C interleaved components, an array holds
//   real:     value c of (i, j, l) at (((i - first_plane) K2 + j) R + l) C + c (doubles)
//   spectrum: value c of (i, j, l) at (((j - first_row) K1 + i) n3 + l) C + c (complex numbers)
// Every call is collective: all ranks make it, in the same order, from the thread that
// initialised MPI (outside OpenMP parallel regions).
#include <fftw3.h>

#include <array>
#include <cstddef>
#include <memory>

#include "libsolver/parallel/communicator.h"

namespace rbcflow {

class SlabFft {
 public:
  // Whether this build has FFTW's MPI library (without it a grid is transformed whole on every
  // rank: spme/spme_grid.h).
  static bool available();

  // flags: FFTW_ESTIMATE or FFTW_MEASURE; threads: the OpenMP threads of each rank's transforms.
  // Throws std::logic_error when !available().
  SlabFft(const Communicator& ranks, const std::array<int, 3>& size, unsigned flags, int threads);
  ~SlabFft();
  SlabFft(const SlabFft&) = delete;
  SlabFft& operator=(const SlabFft&) = delete;

  int first_plane() const { return first_plane_; }
  int planes() const { return planes_; }
  int first_row() const { return first_row_; }
  int rows() const { return rows_; }
  int row_stride() const { return 2 * (size_[2] / 2 + 1); }  // R
  // Complex numbers an array of `components` interleaved grids must hold on this rank, real
  // slab and spectrum block alike (FFTW's transposes may need more than the local block).
  std::size_t buffer_size(int components) const;

  // Plans the transforms of `components` (3 or 1) interleaved grids (forward, and backward for
  // 3) on `data`, an array of buffer_size(components), unless they are planned: planning
  // overwrites it, so call this before anything is written there. A transform planned here
  // needs no array of its own to be planned on (forward() and backward() plan on one they
  // allocate, as large as the caller's, if nothing was planned before).
  void plan_on(fftw_complex* data, int components) const;
  // Forward transform in place of `components` (3 or 1) interleaved real slabs.
  void forward(fftw_complex* data, int components = 3) const;
  // Backward (unnormalised) transform in place of 3 interleaved spectra.
  void backward(fftw_complex* data) const;

 private:
  struct Plans;
  // Plan the transform unless planned: on `on`, or on an array of their own when it is null.
  void plan_forward(int components, fftw_complex* on) const;
  void plan_backward(fftw_complex* on) const;
  std::array<int, 3> size_;
  int first_plane_ = 0, planes_ = 0, first_row_ = 0, rows_ = 0;
  std::size_t alloc3_ = 0, alloc1_ = 0;  // complex numbers FFTW asks for, 3 components and 1
  std::unique_ptr<Plans> plans_;
};

}  // namespace rbcflow
