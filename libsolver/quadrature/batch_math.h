#pragma once
// Elementwise transcendental functions over arrays, for the loops of the correction builds
// that evaluate them at every patch point and every patch node (each build calls them ~10^3
// times per target). They run on glibc's vector math library (libmvec, 4 doubles per call
// with AVX2), within its documented 4 ulp of the scalar functions.
#include <cstddef>

namespace rbcflow {

// out[i] = atan2(y[i], x[i]) in (-pi, pi].
void batch_atan2(const double* y, const double* x, double* out, std::size_t n);
// out[i] = acos(clamp(x[i], -1, 1)).
void batch_acos(const double* x, double* out, std::size_t n);
// eta[i] = the partition-of-unity mask of eq. (31) at rho[i] (patch_mask in polar_patch.h).
void batch_patch_mask(const double* rho, double rho1, double* eta, std::size_t n);

}  // namespace rbcflow
