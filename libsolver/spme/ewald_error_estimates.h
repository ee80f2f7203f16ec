#pragma once
// RMS truncation-error estimates of the Ewald sums (docs/references.md section 2; Lindbo &
// Tornberg, JCP 229 (2010) 8994; af Klinteberg & Tornberg, IJNMF 76 (2014) 669), for random,
// uncorrelated sources.
//
// Every estimate is normalised, so that a tolerance is a dimensionless number: the RMS error
// over targets of the sum (8 pi mu u) divided by
//   sqrt(Q) / ell        (stokeslet, Q = sum_n |f_n|^2),
//   sqrt(Q_T) / ell^2    (stresslet, Q_T = sum_n |q_n|^2 |n_n|^2),
// with ell = V^(1/3) the box's mean side. For N random unit forces in a box this is about a
// fifth of the RMS error relative to the RMS velocity.
#include <array>

#include "libsolver/common/periodic_box.h"

namespace rbcflow {

enum class EwaldKernel { stokeslet, stresslet };  // single layer, double layer

const char* to_string(EwaldKernel kernel);

// Real-space sum truncated at the cutoff r_c:
//   stokeslet e_R = sqrt(8 Q r_c / (3 V)) exp(-xi^2 r_c^2),
//   stresslet e_R = 3.53 xi^2 r_c^(3/2) sqrt(Q_T / V) exp(-xi^2 r_c^2).
double real_space_error(EwaldKernel kernel, const PeriodicBox& box, double xi, double cutoff);

// SPME grid error with B-splines of order p on a grid of K_d points per direction. The model
// sums the squared kernel |K^F(k)|^2 times the squared aliasing of the B-spline interpolation,
// 2 sum_{m != 0} (k_d h_d / (k_d h_d + 2 pi m))^(2p) per direction (spreading and
// interpolation), over all k, and counts every mode beyond the Nyquist wavenumber as lost; the
// result behaves as (h k)^p (REFERENCES section 2) and carries one constant per kernel,
// calibrated against direct Ewald sums (tests/libsolver/spme/test_ewald_error_estimates.cpp).
double spme_grid_error(EwaldKernel kernel, const PeriodicBox& box, double xi,
                       const std::array<int, 3>& grid, int order);
// The same for the spacing h in every direction (h need not divide the box sides).
double spme_grid_error(EwaldKernel kernel, const PeriodicBox& box, double xi, double spacing,
                       int order);

}  // namespace rbcflow
