// Sedimentation of a spherical capsule in a periodic box (issue: coupled solver, validation 1):
// a uniform body-force density translates the sphere rigidly, for every viscosity ratio, with
// the drag of a simple cubic array: K = F / (6 pi mu a U) = 1.53022 (L = 8), 1.38805 (L = 10)
// (docs/references.md section 3). For lambda != 1 this needs the linear part of eq. (3).
#include "libsolver/stepper/cell_velocity.h"

#include <gtest/gtest.h>

#include <numbers>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

TEST(CellVelocity, SedimentingSphereMatchesHasimotoForLambda1And5) {
  const int N = 12;
  const double pi = std::numbers::pi;
  auto grids = CellGrids::make(N, N);
  for (auto [L, K_ref] : {std::pair{8.0, 1.53022}, {10.0, 1.38805}}) {
    SHSurface s = make_sphere(N);
    s.translate(Eigen::Vector3d(0.3 * L, 0.6 * L, 0.5 * L));
    CellLayers layers({s.coeffs()}, grids, LayerDomain{PeriodicBox(Eigen::Vector3d::Constant(L)), 1e-8});
    const Eigen::Vector3d F(0.0, 0.0, -1.0);  // net body force on the cell
    const double area = layers.nodes().weight.sum();
    // Hydrodynamic traction f = (membrane traction, zero here) - body-force density F / A.
    const Eigen::MatrixXd f = (-F / area).transpose().replicate(layers.nodes().size(), 1);
    const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(layers.nodes().size(), 3);
    for (double lambda : {1.0, 5.0}) {
      const VelocitySolve v = solve_cell_velocity(layers, f, lambda, zero, 1e-10, 100);
      ASSERT_TRUE(v.gmres.converged);
      const Eigen::Vector3d U = (v.velocity.array().colwise() * layers.nodes().weight.array()).colwise().sum() / area;
      const double K = F.norm() / (6 * pi * U.norm());
      const double rigid = (v.velocity.rowwise() - U.transpose()).cwiseAbs().maxCoeff() / U.norm();
      std::printf("  L = %4.1f lambda = %.0f: K = %.6f (reference %.5f), GMRES %d, max deviation from rigid %.1e\n", L,
                  lambda, K, K_ref, v.gmres.iterations, rigid);
      EXPECT_NEAR(K / K_ref, 1.0, 0.005);
      EXPECT_GT(U.dot(F), 0.0);
    }
  }
}
