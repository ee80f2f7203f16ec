#pragma once
// Slow, exact reference for the periodic sums of ewald_plan.h (tests only): the same Ewald
// split evaluated without a grid, i.e. the real-space part by brute force over every source
// image within the cutoff (O(targets x sources x images)) and the Fourier part by an explicit
// sum over every k != 0 with |k| <= k_c (O(modes x (sources + targets))).
// Same normalisation, sign (r = x_s - x_t) and r = 0 rule as EwaldPlan.
#include "libsolver/common/periodic_box.h"

namespace rbcflow {

class EwaldDirect {
 public:
  // Default cutoffs r_c = 6.5 / xi and k_c = 13 xi: both truncation errors below 1e-16
  // relative (erfc(6.5) = 4e-20, exp(-(k_c / 2 xi)^2) = 5e-19).
  EwaldDirect(const PeriodicBox& box, double xi);
  EwaldDirect(const PeriodicBox& box, double xi, double real_cutoff, double fourier_cutoff);

  double xi() const { return xi_; }

  PointField single_layer(const PointField& sources, const PointField& forces,
                          const PointField& targets) const;
  PointField double_layer(const PointField& sources, const PointField& q, const PointField& normals,
                          const PointField& targets) const;

  // The two halves separately.
  PointField real_single_layer(const PointField& sources, const PointField& forces,
                               const PointField& targets) const;
  PointField fourier_single_layer(const PointField& sources, const PointField& forces,
                                  const PointField& targets) const;
  PointField real_double_layer(const PointField& sources, const PointField& q,
                               const PointField& normals, const PointField& targets) const;
  PointField fourier_double_layer(const PointField& sources, const PointField& q,
                                  const PointField& normals, const PointField& targets) const;

 private:
  PeriodicBox box_;
  double xi_, real_cutoff_, fourier_cutoff_;
};

}  // namespace rbcflow
