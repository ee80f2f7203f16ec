#include "libsolver/wall/centroid_bins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "geometry/vessel/vessel_mesh.h"

using namespace rbcflow;

// Every centroid within the radius (minimum image; periodic in x and z, not in y) is a
// candidate, and candidates come in ascending order, for points inside and outside the cloud.
TEST(CentroidBins, CandidatesHoldEveryNearCentroidInOrder) {
  const Eigen::Vector3d period(4.0, 0.0, 6.0);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> centroids(2000);
  for (auto& c : centroids) c = Eigen::Vector3d(4.0 * u(gen), -1.0 + 3.0 * u(gen), -0.2 + 6.4 * u(gen));
  for (const double radius : {0.3, 0.7, 5.0}) {
    const CentroidBins bins(centroids, period, radius);
    std::vector<int> got;
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d x(-2.0 + 8.0 * u(gen), -2.0 + 5.0 * u(gen), -3.0 + 12.0 * u(gen));
      bins.candidates(x, got);
      EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
      EXPECT_EQ(std::adjacent_find(got.begin(), got.end()), got.end());
      for (int t = 0; t < static_cast<int>(centroids.size()); ++t) {
        if (minimum_image(centroids[t] - x, period).norm() >= radius) continue;
        EXPECT_TRUE(std::binary_search(got.begin(), got.end(), t)) << "radius " << radius << " triangle " << t;
      }
    }
  }
}
