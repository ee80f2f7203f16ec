#include "libsolver/wall/wall_real_space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "geometry/vessel/vessel.h"
#include "libsolver/wall/wall_operator.h"

using namespace rbcflow;

// The wall operator with its real-space part assembled (wall_real_space.h) has its own Ewald
// parameters (a larger cutoff, a coarser grid): its products agree with the plain operator's
// at a 1e-10 tolerance to the 1e-6 asked, at the wall nodes and at points off the wall, in the
// normalised RMS measure of the tolerance (ewald_error_estimates.h: RMS error times ell over
// the root sum of squares of the Gauss-point densities).
TEST(WallRealSpace, AssembledOperatorMeetsTheEwaldTolerance) {
  const Eigen::Vector3d box(3.0, 3.0, 2.0);
  auto e = std::make_shared<const WallElements>(tube(TubeSpec{2.0, 2, box, 0.4}));
  const PeriodicBox periodic(box);
  PointField off_wall(3, 3);
  off_wall << 1.5, 1.5, 0.3, 1.9, 1.4, 1.0, 0.9, 1.5, 1.7;
  for (const PointField& targets : {PointField(e->wall.surface.points), off_wall}) {
    WallOperator plain(e, targets, periodic, 1e-10),
        assembled(e, targets, periodic, 1e-6, nullptr, WallOperator::RealSpace::assembled);
    const PointField f = PointField::Random(e->num_nodes(), 3);
    const PointField a = plain.apply(f), b = assembled.apply(f);
    const double rms = std::sqrt((a - b).squaredNorm() / a.rows());
    const double ell = std::cbrt(periodic.volume());
    const double normalised = rms * ell / e->weighted_density(f).norm();
    EXPECT_LT(normalised, 1e-6);
  }
}

// A bound on the pairs moves the assembled operator to a cutoff shorter than the near field's
// reach, so that some (target, node) blocks hold only the near-field correction: accurate minus
// Gauss-7 integrals of G that cancel to ~1e-4 of either and keep their rounding's asymmetry.
// The symmetric blocks hold them (their check is against the row's largest entry) and the
// products still meet the tolerance.
TEST(WallRealSpace, AssembledOperatorWithACutoffInsideTheNearField) {
  const Eigen::Vector3d box(3.0, 3.0, 2.0);
  auto e = std::make_shared<const WallElements>(tube(TubeSpec{2.0, 2, box, 0.4}));
  const PeriodicBox periodic(box);
  const PointField& nodes = e->wall.surface.points;
  const RealSpaceUse bounded{kAssembledRealSpace.weight, 20.0 * static_cast<double>(nodes.rows())};
  const EwaldChoice choice = choose_ewald_parameters(EwaldKernel::stokeslet, kAssembledToleranceFactor * 1e-6,
                                                     periodic, e->points.rows(), nodes.rows(), bounded);
  const double near_reach = 3.0 * e->diameters.maxCoeff();  // near_field's default near_factor
  ASSERT_LT(choice.parameters.cutoff, 0.5 * near_reach);
  WallOperator plain(e, nodes, periodic, 1e-10);
  WallOperator assembled(e, nodes, periodic, 1e-6, nullptr, WallOperator::RealSpace::assembled, 0, {}, bounded);
  const PointField f = PointField::Random(e->num_nodes(), 3);
  const PointField a = plain.apply(f), b = assembled.apply(f);
  const double rms = std::sqrt((a - b).squaredNorm() / a.rows());
  const double normalised = rms * std::cbrt(periodic.volume()) / e->weighted_density(f).norm();
  EXPECT_LT(normalised, 1e-6);
}
