#pragma once
// The in-place 3-D real transform of C interleaved grids of size K = (K1, K2, K3) in FFTW's r2c
// layout (real rows padded to R = 2 (K3/2 + 1) values; value c of (i, j, l) at
// ((i K2 + j) R + l) C + c), taken as FFTW does it but planned piece by piece:
//   forward:  per plane i: the rows' r2c transforms along l, then c2c along j (one plane after
//             the other, each while it is in cache); then c2c along i, in blocks of kColumnBlock
//             neighbouring columns of the K2 (K3/2 + 1) C that the planes hold;
//   backward: the same in reverse order (c2c along i, then per plane c2c along j and c2r along l).
// The plans are single-threaded plans of one row, one plane and one block, executed on every
// row, plane and block in OpenMP loops (FFTW's new-array execution is thread-safe). FFTW_MEASURE plans these
// in under a second where it planned the whole 3-D transform in 20-50 s for the 162 x 162 x 1600
// grid of the 1,000-cell tube, and the transforms run as fast (docs/performance.md, "FFT plans").
#include <fftw3.h>

#include <array>
#include <cstddef>

namespace rbcflow {

class GridTransform {
 public:
  // Plans on `on` (overwritten; C K1 K2 (K3/2 + 1) complex numbers, FFTW-aligned) with `flags`
  // (FFTW_ESTIMATE or FFTW_MEASURE); the caller holds fftw_planner_mutex() (fftw_util.h).
  // Throws std::runtime_error if FFTW cannot plan it.
  GridTransform(const std::array<int, 3>& size, int components, bool forward, unsigned flags, fftw_complex* on);
  ~GridTransform();  // takes fftw_planner_mutex() itself
  GridTransform(const GridTransform&) = delete;
  GridTransform& operator=(const GridTransform&) = delete;

  // In place on an array like the one planned on (any FFTW-aligned array of that size).
  void execute(fftw_complex* data) const;

 private:
  void planes(fftw_complex* data) const;
  void columns(fftw_complex* data) const;

  std::array<int, 3> size_;
  bool forward_;
  std::size_t row_;    // complex numbers per row: (K3/2 + 1) C
  std::size_t plane_;  // per plane: K2 rows, the columns along i
  int blocks_;         // of kColumnBlock columns, the last one `rest_`'s if it is shorter
  fftw_plan rows_ = nullptr, middle_ = nullptr, block_ = nullptr, rest_ = nullptr;
};

}  // namespace rbcflow
