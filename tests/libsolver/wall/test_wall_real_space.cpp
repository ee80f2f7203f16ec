#include "libsolver/wall/wall_real_space.h"

#include <gtest/gtest.h>

#include <memory>

#include "geometry/vessel.h"
#include "libsolver/wall/wall_operator.h"

using namespace rbcflow;

// The wall operator with its real-space part assembled (wall_real_space.h) gives the products
// of the plain one to rounding, at the wall nodes and at points off the wall.
TEST(WallRealSpace, AssembledOperatorMatchesPlainProducts) {
  const Eigen::Vector3d box(3.0, 3.0, 2.0);
  auto e = std::make_shared<const WallElements>(tube(TubeSpec{2.0, 2, box, 0.4}));
  const PeriodicBox periodic(box);
  PointField off_wall(3, 3);
  off_wall << 1.5, 1.5, 0.3, 1.9, 1.4, 1.0, 0.9, 1.5, 1.7;
  for (const PointField& targets : {PointField(e->wall.surface.points), off_wall}) {
    WallOperator plain(e, targets, periodic, 1e-6), assembled(e, targets, periodic, 1e-6);
    assembled.assemble_real_space();
    const PointField f = PointField::Random(e->num_nodes(), 3);
    const PointField a = plain.apply(f), b = assembled.apply(f);
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12 * a.cwiseAbs().maxCoeff());
  }
}
