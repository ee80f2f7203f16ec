#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "geometry/vessel/vessel_branches.h"

using namespace rbcflow;

namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

// The disk quadrature: area pi r^2, the Poiseuille profile's flux pi r^4 / 2 (1 - rho^2 / r^2
// times r^2), and a tilted disk's points in its plane at most r from its centre.
TEST(VesselBranch, SectionQuadratureIntegratesTheDisk) {
  const VesselBranch b{{1, 2, 3}, {2, 4, 5}, 0.7};
  const SectionQuadrature q = section_quadrature(b, 6, 16);
  EXPECT_NEAR(q.weights.sum(), kPi * 0.49, 1e-13);
  double poiseuille = 0, cos2 = 0;
  const Eigen::Vector3d e = q.normal.unitOrthogonal();
  for (int i = 0; i < q.points.rows(); ++i) {
    const Eigen::Vector3d d = q.points.row(i).transpose() - b.centre();
    EXPECT_NEAR(d.dot(q.normal), 0.0, 1e-14);
    EXPECT_LE(d.norm(), 0.7);
    poiseuille += q.weights[i] * (0.49 - d.squaredNorm());
    cos2 += q.weights[i] * std::pow(d.dot(e), 2);
  }
  EXPECT_NEAR(poiseuille, kPi * std::pow(0.7, 4) / 2, 1e-13);
  EXPECT_NEAR(cos2, kPi * std::pow(0.7, 4) / 4, 1e-13);  // integral of x^2 over the disk
  EXPECT_NEAR(q.normal.dot((b.to - b.from).normalized()), 1.0, 1e-15);
}

// The bifurcation of data/cases/bifurcation.toml: the parent on the axis through the box face,
// the daughters at +-offset in x, and points assigned to the branch they are in.
TEST(VesselBranch, BifurcationBranchesAndNearest) {
  BifurcationSpec s;
  s.tube = {3.0, 2, Eigen::Vector3d(12, 6, 16), 0.3};
  s.daughter_diameters = {2.4, 2.2};
  s.angle_deg = 60;
  s.centre = 5;
  const std::vector<VesselBranch> b = bifurcation_branches(s);
  ASSERT_EQ(b.size(), 3u);
  const double offset = bifurcation_layout(s).offset;
  EXPECT_EQ(b[0].centre(), Eigen::Vector3d(6, 3, 1));  // between the merge at 13 - 16 and the split at 5
  EXPECT_EQ(b[1].centre(), Eigen::Vector3d(6 + offset, 3, 9));
  EXPECT_EQ(b[2].centre(), Eigen::Vector3d(6 - offset, 3, 9));
  EXPECT_DOUBLE_EQ(b[1].radius, 1.2);
  const Eigen::Vector3d period(0, 0, 16);
  EXPECT_EQ(nearest_branch(b, Eigen::Vector3d(6, 3, 15), period), 0);  // past the merge, through the face
  EXPECT_EQ(nearest_branch(b, Eigen::Vector3d(6.2, 3, 2), period), 0);
  EXPECT_EQ(nearest_branch(b, Eigen::Vector3d(6 + offset, 3.3, 9), period), 1);
  EXPECT_EQ(nearest_branch(b, Eigen::Vector3d(6 - offset - 0.5, 3, 11), period), 2);
}

// A tube is one branch along its axis; a constriction's section is half a box from its neck.
TEST(VesselBranch, TubeAndConstrictionAreOneBranch) {
  const TubeSpec t{4.0, 0, Eigen::Vector3d(10, 6, 6), 0.3};
  const std::vector<VesselBranch> tb = tube_branches(t);
  ASSERT_EQ(tb.size(), 1u);
  EXPECT_EQ(tb[0].from, Eigen::Vector3d(0, 3, 3));
  EXPECT_EQ(tb[0].to, Eigen::Vector3d(10, 3, 3));
  ConstrictionSpec c;
  c.tube = t;
  c.centre = 2.0;
  EXPECT_EQ(constriction_branches(c)[0].centre(), Eigen::Vector3d(7, 3, 3));
}
