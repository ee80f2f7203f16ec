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
