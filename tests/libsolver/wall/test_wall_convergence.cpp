// Mesh convergence of the wall solve (slow: ctest -L slow): the error of the effective
// viscosity falls at second order in the element size, and the GMRES iteration count stays
// bounded as the element count grows 4x. Prints the table.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "wall_poiseuille.h"

using namespace rbcflow;

TEST(WallConvergence, EffectiveViscosityConvergesAtSecondOrder) {
  const double D = 6.0, side = 8.0, length = 3.0;
  std::vector<double> hs{0.48, 0.34, 0.24, 0.17};
  std::vector<test::TubeFlowResult> r;
  std::printf("%8s %10s %10s %12s %12s %12s %8s\n", "h", "triangles", "iterations", "mu_eff - 1",
              "centre - 1", "max slip", "order");
  for (double h : hs) {
    r.push_back(test::tube_flow(D, side, length, h));
    const auto& x = r.back();
    const double order = r.size() > 1 ? std::log(std::abs((r[r.size() - 2].mu_eff - 1) / (x.mu_eff - 1))) /
                                             std::log(hs[r.size() - 2] / h)
                                       : 0.0;
    std::printf("%8.3f %10d %10d %12.3e %12.3e %12.3e %8.2f\n", h, x.triangles, x.iterations,
                x.mu_eff - 1, x.centreline_ratio - 1, x.max_slip, order);
  }
  const double order = std::log(std::abs((r[0].mu_eff - 1) / (r[3].mu_eff - 1))) / std::log(hs[0] / hs[3]);
  EXPECT_GT(order, 1.7);
  // 4x the elements from hs[1] to hs[3]: the iteration count must not grow by more than 50%.
  EXPECT_LE(r[3].iterations, 1.5 * r[1].iterations);
}
