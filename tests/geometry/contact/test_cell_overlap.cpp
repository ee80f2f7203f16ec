#include "geometry/contact/cell_overlap.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "geometry/contact/wall_distance.h"
#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"

using namespace rbcflow;

namespace {

// The overlap tests take the vertices of the check triangulation (order 16: spacing about
// pi / 16 = 0.2 on a unit sphere) against the other's triangles (chords: at most 0.2^2 / 8 =
// 0.005 inside the sphere). Two unit spheres at centre distance d overlap by 2 + gap - d; a vertex
// of one lies inside the other's cap when that overlap exceeds (spacing / 2)^2 / 2 = 0.005. Within
// kBand of the analytic contact distance either answer is allowed; outside it, the analytic one.
constexpr int kCheckOrder = 16;
constexpr double kGap = 0.05, kBand = 0.02;

Eigen::Vector3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  return Eigen::Quaterniond(Eigen::Vector4d(random_unit(rng).homogeneous().normalized())).toRotationMatrix();
}

}  // namespace

// Every pair answer against the analytic one for spheres (radius 1 scaled by s), in free space and
// through the images of a periodic box: apart exactly when the centres are at least 2 s + gap apart.
TEST(CellOverlap, SpheresAreApartExactlyBeyondContact) {
  const SHSurface sphere = make_sphere(8);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> margin(-0.3, 0.3), scale(0.5, 1.0);
  for (const Eigen::Vector3d& period : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 5.0)}) {
    const CellOverlap overlap(sphere, kCheckOrder, period, nullptr, kGap);
    int apart = 0, touching = 0;
    for (int trial = 0; trial < 400; ++trial) {
      CellPose a, b;
      a.rotation = random_rotation(rng);
      b.rotation = random_rotation(rng);
      a.scale = b.scale = scale(rng);
      const double contact = 2.0 * a.scale + kGap, d = contact + margin(rng);
      if (std::abs(d - contact) < kBand) continue;
      a.position = Eigen::Vector3d(0.5, -0.2, 1.0);
      b.position = a.position + d * random_unit(rng);
      if (period.z() > 0) b.position.z() += period.z();  // the image one period along meets a
      const bool expected = d > contact;
      EXPECT_EQ(overlap.apart(a, b), expected) << "d " << d << ", contact " << contact;
      EXPECT_EQ(overlap.apart(b, a), expected) << "d " << d << ", contact " << contact;
      (expected ? apart : touching) += 1;
    }
    EXPECT_GT(apart, 100);
    EXPECT_GT(touching, 100);
  }
}

// Inside a straight tube of diameter 4 (facets of size 0.2: chords at most 0.2^2 / 16 = 0.0025
// inside the circle): a sphere of radius s at distance r from the axis is inside with the gap
// exactly when r + s + gap <= 2.
TEST(CellOverlap, SphereInsideTubeExactlyWithinTheLumen) {
  const SHSurface sphere = make_sphere(8);
  const VesselMesh mesh = tube(TubeSpec{4.0, 2, Eigen::Vector3d(5, 5, 6), 0.2});
  const WallDistance wall(mesh);
  const CellOverlap overlap(sphere, kCheckOrder, Eigen::Vector3d(0, 0, 6), &wall, kGap);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> offset(0.4, 2.0), scale(0.3, 1.0), along(-3.0, 9.0), turn(0, 2 * std::numbers::pi);
  int inside = 0, crossing = 0;
  for (int trial = 0; trial < 400; ++trial) {
    CellPose p;
    p.rotation = random_rotation(rng);
    p.scale = scale(rng);
    const double r = offset(rng), edge = r + p.scale + kGap - 2.0;
    if (std::abs(edge) < kBand) continue;
    const double angle = turn(rng);
    p.position = Eigen::Vector3d(2.5 + r * std::cos(angle), 2.5 + r * std::sin(angle), along(rng));
    EXPECT_EQ(overlap.inside_wall(p), edge < 0) << "offset " << r << ", scale " << p.scale;
    (edge < 0 ? inside : crossing) += 1;
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(crossing, 100);
}

// The reference of random placement carries a table of its signed distance (distance_bounds.h)
// that lets points clearly apart skip their closest-point query; the answers are those of the
// queries alone (the same surface as a listed body, which has no table), for red cells in
// every orientation at scales and distances around contact.
TEST(CellOverlap, DistanceTableKeepsEveryAnswer) {
  const SHSurface rbc = make_biconcave(16);
  const Eigen::Vector3d period(0, 0, 6.0);
  const CellOverlap with_table(rbc, kCheckOrder, period, nullptr, kGap);
  const CellOverlap queries_only(std::vector<SHSurface>{rbc}, kCheckOrder, period, nullptr, kGap);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> distance(0.7, 3.0), scale(0.6, 1.0);
  int apart = 0, touching = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    CellPose a, b;
    a.rotation = random_rotation(rng);
    b.rotation = random_rotation(rng);
    a.scale = scale(rng);
    b.scale = scale(rng);
    a.position = Eigen::Vector3d(0.3, 0.1, 0.5);
    b.position = a.position + distance(rng) * random_unit(rng);
    const bool expected = queries_only.apart(a, b);
    ASSERT_EQ(with_table.apart(a, b), expected) << "trial " << trial;
    (expected ? apart : touching) += 1;
  }
  EXPECT_GT(apart, 400);
  EXPECT_GT(touching, 400);
}
