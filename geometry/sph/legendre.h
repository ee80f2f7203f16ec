#pragma once
// Normalised associated Legendre functions of the paper's eq. (14)-(15) (no Condon-Shortley
// phase, integral of Pbar^2 over [-1, 1] equal to 1) and their derivatives in colatitude.
#include <Eigen/Core>
#include <vector>

namespace rbcflow {

// tables[k][m] is an (n_theta x (L - m)) matrix whose column n - m holds
// d^k/dtheta^k Pbar_n^m(cos theta_i), for 0 <= m <= n < L and 0 <= k <= max_derivative.
// Values come from the stable three-term recurrence in n; derivatives from the exact relation
//   dPbar_n^m/dtheta = (sqrt((n+m)(n-m+1)) Pbar_n^{m-1} - sqrt((n-m)(n+m+1)) Pbar_n^{m+1}) / 2
// with Pbar_n^{-1} = -Pbar_n^1, applied k times: no division by sin(theta), no pole case.
using LegendreTables = std::vector<std::vector<Eigen::MatrixXd>>;
LegendreTables legendre_theta_tables(const Eigen::VectorXd& theta, int L, int max_derivative);

// The same at one colatitude, for point evaluations in hot loops (surface projection): no
// allocation, the recurrence coefficients of each L computed once per thread;
// legendre_theta_tables is this, colatitude by colatitude. d^k/dtheta^k Pbar_n^m goes to
// p[k * legendre_size(L) + legendre_index(L, n, m)]; p holds (max_derivative + 1) legendre_size(L).
constexpr int legendre_size(int L) { return L * (L + 1) / 2; }
constexpr int legendre_index(int L, int n, int m) { return m * L - m * (m - 1) / 2 + (n - m); }
void legendre_theta_point(double theta, int L, int max_derivative, double* p);

}  // namespace rbcflow
