#pragma once
// Poiseuille flow in a periodic tube without cells, driven by the mean velocity <u> = e_z:
// the shared set-up of the wall-solver tests.
#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <numbers>

#include "geometry/vessel/vessel.h"
#include "libsolver/wall/tube_flow.h"
#include "libsolver/wall/wall_solver.h"

namespace rbcflow::test {

struct TubeFlowResult {
  int triangles = 0;
  int iterations = 0;
  double mu_eff = 0;            // eq. (45)-(46)
  double centreline_ratio = 0;  // centreline velocity / (2 x the tube's mean velocity)
  double max_slip = 0;          // max |u| at triangle centroids / the tube's mean velocity
};

inline TubeFlowResult tube_flow(double diameter, double side, double length, double h) {
  TubeSpec spec;
  spec.diameter = diameter;
  spec.box = Eigen::Vector3d(side, side, length);
  spec.element_size = h;
  auto e = std::make_shared<const WallElements>(tube(spec));
  const PeriodicBox box(spec.box);
  const double ewald_tolerance = 1e-8;
  WallSolver solver(
      WallOperator(e, e->wall.surface.points, box, ewald_tolerance, nullptr, WallOperator::RealSpace::assembled));
  const Eigen::RowVector3d mean(0, 0, 1);
  const WallSolution s = solver.solve(mean.replicate(e->num_nodes(), 1), 1.0);

  TubeFlowResult r;
  r.triangles = e->num_triangles();
  r.iterations = s.gmres.iterations;
  const double a = 0.5 * diameter;
  const double dpdz = mean_pressure_gradient(*e, s.force, box.volume())[2];
  r.mu_eff = tube_effective_viscosity(a, side, 1.0, dpdz);
  const double tube_mean = a * a * (-dpdz) / (8.0 * r.mu_eff);  // Q_tube / (pi a^2)

  // u = <u> - N_W f / (8 pi mu) on the axis and at the centroids.
  PointField axis(8, 3), centroids(e->num_triangles(), 3);
  for (int k = 0; k < 8; ++k) axis.row(k) << 0.5 * side, 0.5 * side, length * (k + 0.5) / 8;
  for (int t = 0; t < e->num_triangles(); ++t) centroids.row(t) = e->vertices[t].rowwise().mean().transpose();
  const double scale = 1.0 / (8.0 * std::numbers::pi);
  const PointField u_axis = (-scale * WallOperator(e, axis, box, ewald_tolerance).apply(s.force)).rowwise() + mean;
  const PointField u_wall = (-scale * WallOperator(e, centroids, box, ewald_tolerance).apply(s.force)).rowwise() + mean;
  r.centreline_ratio = u_axis.col(2).mean() / (2.0 * tube_mean);
  r.max_slip = u_wall.rowwise().norm().maxCoeff() / tube_mean;
  return r;
}

}  // namespace rbcflow::test
