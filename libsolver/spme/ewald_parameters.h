#pragma once
// Parameters of a periodic Ewald sum (real-space part by cell lists, smooth part by SPME) and
// the one call that chooses them from a user tolerance.
#include <array>
#include <iosfwd>
#include <string>

#include "ewald_error_estimates.h"
#include "libsolver/common/periodic_box.h"

namespace rbcflow {

struct EwaldParameters {
  double xi = 0.0;            // ewald_xi, Hasimoto's splitting parameter (paper: alpha = pi/xi^2)
  double cutoff = 0.0;        // real-space cutoff radius r_c (may exceed half a box side)
  std::array<int, 3> grid{};  // SPME grid points K_d per direction
  int order = 0;              // B-spline order p, 4 .. 10

  double alpha() const;  // the paper's alpha = pi / xi^2
};

// Throws std::invalid_argument with a message naming the bad parameter.
void validate(const EwaldParameters& p, const PeriodicBox& box);

// What choose_ewald_parameters decided and why; prints as a few lines for `rbcflow check`.
struct EwaldChoice {
  EwaldParameters parameters;
  EwaldKernel kernel = EwaldKernel::stokeslet;
  double tolerance = 0.0;
  double real_space_error = 0.0;  // normalised estimates (ewald_error_estimates.h)
  double grid_error = 0.0;
  double neighbours_per_target = 0.0;
  double estimated_seconds = 0.0;  // modelled time of one product, 1 thread
};

// Smallest estimated cost of one product (real-space pairs, B-spline spreading and
// interpolation, FFTs, influence function; 2-core development machine, 1 thread) over the
// splitting parameter xi and the spline order p = 4 .. 10, subject to the estimated error
//   sqrt(e_real^2 + e_grid^2) <= tolerance / 2
// (a factor 2 of margin for the ~1.5x accuracy of the estimates). The grid sides are even
// FFT-friendly sizes (2^a 3^b 5^c 7^d) of nearly equal spacing. `tolerance` is the
// normalised RMS error of ewald_error_estimates.h, between 1e-10 and 1e-3; n_targets < 0
// means as many targets as sources. `real_space` says how the caller evaluates the real-space
// sum (below). Throws std::invalid_argument for bad input.
struct RealSpaceUse;
EwaldChoice choose_ewald_parameters(EwaldKernel kernel, double tolerance, const PeriodicBox& box,
                                    long n_sources, long n_targets = -1);
EwaldChoice choose_ewald_parameters(EwaldKernel kernel, double tolerance, const PeriodicBox& box,
                                    long n_sources, long n_targets, const RealSpaceUse& real_space);

// How the real-space sum is evaluated, for the cost model: pair by pair at every product
// (the default), or assembled once as a sparse matrix and applied many times (the wall solve,
// wall_real_space.h), where a pair costs a fraction `weight` of a kernel evaluation; the choice
// then moves to a larger cutoff and a coarser grid, bounded by `max_pairs` (memory).
struct RealSpaceUse {
  double weight = 1.0;
  double max_pairs = 1e9;
};

std::ostream& operator<<(std::ostream& os, const EwaldParameters& p);
std::ostream& operator<<(std::ostream& os, const EwaldChoice& c);
std::string to_string(const EwaldChoice& c);

}  // namespace rbcflow
