#include "spme_plan.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "libsolver/common/memory_report.h"

namespace rbcflow {
namespace {

double seconds_since(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

void check_rows(const PointField& field, int n, const char* what) {
  if (field.rows() != n)
    throw std::invalid_argument(std::string("SPME: ") + what + " has " +
                                std::to_string(field.rows()) + " rows for " + std::to_string(n) +
                                " sources");
}

}  // namespace

SpmePlan::SpmePlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources,
                   const PointField& targets)
    : grid_(std::move(grid)),
      sources_(std::make_shared<const SpmeStencils>(*grid_, sources)),
      targets_(std::make_shared<const SpmeStencils>(*grid_, targets)) {}

SpmePlan::SpmePlan(std::shared_ptr<const SpmeGrid> grid, const PointField& points)
    : grid_(std::move(grid)),
      sources_(std::make_shared<const SpmeStencils>(*grid_, points)),
      targets_(sources_) {}

PointField SpmePlan::single_layer(const PointField& forces) {
  check_rows(forces, n_sources(), "the force field");
  auto t = std::chrono::steady_clock::now();
  std::vector<double> density(3 * static_cast<std::size_t>(n_sources()));
  WorkArray grid = grid_->work_array(3);
#pragma omp parallel for schedule(static)
  for (int s = 0; s < n_sources(); ++s)
    for (int c = 0; c < 3; ++c) density[3 * static_cast<std::size_t>(s) + c] = forces(s, c);
  sources_->spread<3>(density.data(), SpmeGrid::real_part(grid.data()));
  return convolve_stokeslet(grid, t);
}

PointField SpmePlan::single_layer(const SpmeStencils::SpreadingMatrix& spreading, const PointField& x) {
  const auto slab_points = static_cast<Eigen::Index>(grid_->slab_points());
  if (spreading.rows() != slab_points || spreading.cols() != x.rows())
    throw std::invalid_argument("SPME: a spreading matrix of " + std::to_string(spreading.rows()) + " x " +
                                std::to_string(spreading.cols()) + " for " + std::to_string(x.rows()) +
                                " unknowns on a grid of " + std::to_string(slab_points) + " points");
  auto t = std::chrono::steady_clock::now();
  std::vector<double> density(3 * static_cast<std::size_t>(x.rows()));
  WorkArray buffer = grid_->work_array(3);
  for (Eigen::Index n = 0; n < x.rows(); ++n)
    for (int c = 0; c < 3; ++c) density[3 * static_cast<std::size_t>(n) + c] = x(n, c);
  const double* in = density.data();
  double* grid = SpmeGrid::real_part(buffer.data());
#pragma omp parallel for schedule(dynamic, 4096)
  for (Eigen::Index g = 0; g < spreading.rows(); ++g) {
    double a = 0.0, b = 0.0, c = 0.0;
    for (SpmeStencils::SpreadingMatrix::InnerIterator it(spreading, g); it; ++it) {
      const double* v = in + 3 * static_cast<std::size_t>(it.col());
      a += it.value() * v[0];
      b += it.value() * v[1];
      c += it.value() * v[2];
    }
    grid[3 * g] = a;
    grid[3 * g + 1] = b;
    grid[3 * g + 2] = c;
  }
  return convolve_stokeslet(buffer, t);
}

PointField SpmePlan::convolve_stokeslet(WorkArray& grid, std::chrono::steady_clock::time_point t) {
  timings_.spreading = seconds_since(t);
  grid_->forward(grid.data());
  timings_.fft = seconds_since(t);
  grid_->apply_stokeslet(grid.data());
  timings_.influence = seconds_since(t);
  return transform_and_interpolate(grid);
}

PointField SpmePlan::double_layer(const PointField& q, const PointField& normals) {
  check_rows(q, n_sources(), "the double-layer density");
  check_rows(normals, n_sources(), "the normal field");
  auto t = std::chrono::steady_clock::now();
  // The symmetric part of q n^T (T is symmetric) in parts: the diagonal (xx, yy, zz) spread,
  // transformed and turned into the velocity's spectra in place, then the off-diagonal part
  // (xy, xz, yz) in an array of its own, its velocity added: the three components together
  // (48 bytes a grid point with the velocity's array) or, lean, one at a time (32 bytes; all six
  // out of place took 96): the largest memory of a product.
  timings_ = {};
  const int n = n_sources();
  std::vector<double> density(3 * static_cast<std::size_t>(n));
  WorkArray velocity = grid_->work_array(3);
#pragma omp parallel for schedule(static)
  for (int s = 0; s < n; ++s)
    for (int c = 0; c < 3; ++c) density[3 * static_cast<std::size_t>(s) + c] = q(s, c) * normals(s, c);
  sources_->spread<3>(density.data(), SpmeGrid::real_part(velocity.data()));
  timings_.spreading += seconds_since(t);
  grid_->forward(velocity.data());
  timings_.fft += seconds_since(t);
  grid_->apply_stresslet(0, 3, velocity.data(), velocity.data(), false);
  timings_.influence += seconds_since(t);
  {
    const int width = lean_ ? 1 : 3;
    WorkArray part = grid_->work_array(width);
    constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};  // xy, xz, yz
    for (int first = 0; first < 3; first += width) {
#pragma omp parallel for schedule(static)
      for (int s = 0; s < n; ++s)
        for (int c = 0; c < width; ++c) {
          const int a = kPairs[first + c][0], b = kPairs[first + c][1];
          density[width * static_cast<std::size_t>(s) + c] = 0.5 * (q(s, a) * normals(s, b) + q(s, b) * normals(s, a));
        }
      if (lean_) {
        sources_->spread<1>(density.data(), SpmeGrid::real_part(part.data()));
      } else {
        sources_->spread<3>(density.data(), SpmeGrid::real_part(part.data()));
      }
      timings_.spreading += seconds_since(t);
      grid_->forward(part.data(), width);
      timings_.fft += seconds_since(t);
      grid_->apply_stresslet(3 + first, width, part.data(), velocity.data(), true);
      timings_.influence += seconds_since(t);
    }
  }
  std::vector<double>().swap(density);
  return transform_and_interpolate(velocity);
}

PointField SpmePlan::transform_and_interpolate(WorkArray& velocity) {
  auto t = std::chrono::steady_clock::now();
  grid_->backward(velocity.data());
  timings_.fft += seconds_since(t);
  PointField u;
  targets_->interpolate(SpmeGrid::real_part(velocity.data()), u);
  timings_.interpolation = seconds_since(t);
  return u;
}

std::size_t SpmePlan::stencil_bytes() const {
  return sources_->memory_bytes() + (targets_ == sources_ ? 0 : targets_->memory_bytes());
}

std::size_t SpmePlan::work_bytes(int components) const {
  // The single layer holds its density and one array of 3 grids (transformed in place) for its
  // product; the double layer the same and an array of 3 grids or, lean, of one besides
  // (double_layer()).
  const std::size_t array = grid_->buffer_size(3) * sizeof(fftw_complex);
  const std::size_t three = 3 * static_cast<std::size_t>(n_sources()) * sizeof(double) + array;
  return components == 6 ? three + grid_->buffer_size(lean_ ? 1 : 3) * sizeof(fftw_complex) : three;
}

}  // namespace rbcflow
