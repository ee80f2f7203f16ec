#pragma once
// Cardinal B-splines for smooth particle-mesh Ewald (Essmann et al., J. Chem. Phys. 103
// (1995) 8577, section 3): M_p has support [0, p], M_1 = 1 on [0, 1) and
// M_p(u) = [u M_{p-1}(u) + (p - u) M_{p-1}(u - 1)] / (p - 1).
#include <vector>

namespace rbcflow {

inline constexpr int kMinSplineOrder = 4;
inline constexpr int kMaxSplineOrder = 10;

// Throws std::invalid_argument unless kMinSplineOrder <= order <= kMaxSplineOrder.
void check_spline_order(int order);

// M_p(u) for any real u (0 outside (0, p)).
double bspline(int order, double u);

// w[j] = M_p(t + j), j = 0 .. p-1, for t in [0, 1): the weights of the p grid points
// floor(u) - j around a point at grid coordinate u = floor(u) + t. They sum to 1.
void bspline_weights(int order, double t, double* w);

// |sum_{j=0}^{p-2} M_p(j + 1) exp(2 pi i m j / K)|^2 for m = 0 .. K-1, i.e. 1 / |b(m)|^2 of
// Essmann's eq. (4.4): SPME divides the influence function by the product of these over the
// three directions. For odd p it vanishes at m = K/2 (SPME drops that mode).
std::vector<double> bspline_modulus(int order, int grid_size);

}  // namespace rbcflow
