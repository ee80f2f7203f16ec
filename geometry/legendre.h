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

}  // namespace rbcflow
