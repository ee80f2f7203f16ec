#include "grid_transform.h"

#include <mutex>
#include <stdexcept>

#include "geometry/sph/fftw_util.h"

namespace rbcflow {
namespace {

// Neighbouring columns transformed together along the first direction: 8 complex numbers are
// two cache lines of each of the K1 planes (4 to 64 measured; 8 was the fastest on the
// 162 x 162 x 1600 grid, docs/performance.md).
constexpr int kColumnBlock = 8;

}  // namespace

GridTransform::GridTransform(const std::array<int, 3>& size, int components, bool forward, unsigned flags,
                             fftw_complex* on)
    : size_(size), forward_(forward) {
  const int C = components, n3 = size[2] / 2 + 1;
  row_ = static_cast<std::size_t>(n3) * C;
  plane_ = size[1] * row_;
  const int columns = static_cast<int>(plane_);
  blocks_ = (columns + kColumnBlock - 1) / kColumnBlock;
  const int rest = columns - (blocks_ - 1) * kColumnBlock;
  const int sign = forward ? FFTW_FORWARD : FFTW_BACKWARD;
  double* real = reinterpret_cast<double*>(on);
  // New-array execution needs arrays of the planned alignment (FFTW manual, 4.6): rows or planes
  // of an odd number of complex numbers alternate in it, so their plans then take any.
  const auto same_alignment = [&](std::size_t complex_offset) {
    return fftw_alignment_of(real + 2 * complex_offset) == fftw_alignment_of(real);
  };
  const unsigned row_flags = same_alignment(row_) ? flags : flags | FFTW_UNALIGNED;
  const unsigned plane_flags = same_alignment(plane_) ? flags : flags | FFTW_UNALIGNED;
  // Along l: K3 points C apart (doubles, or complex numbers of the spectrum), for each of the
  // row's C components. (One row at a time: FFTW plans no in-place c2r over rows and components
  // at once, whose outputs would overwrite other transforms' inputs.)
  const fftw_iodim along_l{size[2], C, C};
  const fftw_iodim components_of_row{C, 1, 1};
  // Along j: K2 points n3 C apart, for each of the n3 C columns of a plane.
  const fftw_iodim along_j{size[1], n3 * C, n3 * C};
  const fftw_iodim plane_columns{n3 * C, 1, 1};
  // Along i: K1 points a plane apart, for each column of a block.
  const fftw_iodim along_i{size[0], columns, columns};
  const fftw_iodim block{kColumnBlock, 1, 1}, last_block{rest, 1, 1};
  rows_ = forward ? fftw_plan_guru_dft_r2c(1, &along_l, 1, &components_of_row, real, on, row_flags)
                  : fftw_plan_guru_dft_c2r(1, &along_l, 1, &components_of_row, on, real, row_flags);
  middle_ = fftw_plan_guru_dft(1, &along_j, 1, &plane_columns, on, on, sign, plane_flags);
  if (blocks_ > 1) block_ = fftw_plan_guru_dft(1, &along_i, 1, &block, on, on, sign, flags);
  rest_ = fftw_plan_guru_dft(1, &along_i, 1, &last_block, on, on, sign, flags);
  if (!rows_ || !middle_ || (blocks_ > 1 && !block_) || !rest_) {
    for (fftw_plan p : {rows_, middle_, block_, rest_})
      if (p) fftw_destroy_plan(p);
    throw std::runtime_error("SPME: FFTW could not plan the grid transform");
  }
}

GridTransform::~GridTransform() {
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  for (fftw_plan p : {rows_, middle_, block_, rest_})
    if (p) fftw_destroy_plan(p);
}

void GridTransform::planes(fftw_complex* data) const {
#pragma omp parallel for schedule(static)
  for (int i = 0; i < size_[0]; ++i) {
    fftw_complex* plane = data + i * plane_;
    if (!forward_) fftw_execute_dft(middle_, plane, plane);
    for (int j = 0; j < size_[1]; ++j) {
      fftw_complex* row = plane + static_cast<std::size_t>(j) * row_;
      double* real = reinterpret_cast<double*>(row);
      if (forward_) {
        fftw_execute_dft_r2c(rows_, real, row);
      } else {
        fftw_execute_dft_c2r(rows_, row, real);
      }
    }
    if (forward_) fftw_execute_dft(middle_, plane, plane);
  }
}

void GridTransform::columns(fftw_complex* data) const {
#pragma omp parallel for schedule(static)
  for (int b = 0; b < blocks_; ++b) {
    fftw_complex* first = data + static_cast<std::size_t>(b) * kColumnBlock;
    fftw_execute_dft(b + 1 < blocks_ ? block_ : rest_, first, first);
  }
}

void GridTransform::execute(fftw_complex* data) const {
  if (forward_) {
    planes(data);
    columns(data);
  } else {
    columns(data);
    planes(data);
  }
}

}  // namespace rbcflow
