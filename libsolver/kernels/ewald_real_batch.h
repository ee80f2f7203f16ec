#pragma once
// The real-space split coefficients of ewald_kernels.h (eq. 24 and 27) for many pairs at once,
// for the real-space sums' inner loops: the pairs' separations r = (x, y, z) in three arrays,
// the coefficients out in two. The loops vectorise (4 pairs an instruction with AVX2) with
// erfc and exp from glibc's vector math library (libmvec, within its documented 4 ulp of the
// scalar functions), where a pair of EwaldRealKernel costs a scalar exp, sqrt and polynomial.
// Every r must be non-zero.

namespace rbcflow {

// S^R(r) f = a f + b (r.f) r: a = erfc(xi r)/r - (2 xi/sqrt(pi)) e^{-xi^2 r^2},
// b = (erfc(xi r)/r + (2 xi/sqrt(pi)) e^{-xi^2 r^2}) / r^2.
void batch_stokeslet_coeffs(double xi, const double* x, const double* y, const double* z, int n, double* a,
                            double* b);

// T^R_ijk(r) q_j n_k = (alpha (r.q)(r.n) + beta q.n) r_i + beta ((r.n) q_i + (r.q) n_i), alpha and
// beta of StressletSplitCoeffs.
void batch_stresslet_coeffs(double xi, const double* x, const double* y, const double* z, int n, double* alpha,
                            double* beta);

}  // namespace rbcflow
