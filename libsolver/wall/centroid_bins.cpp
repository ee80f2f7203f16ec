#include "centroid_bins.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rbcflow {

CentroidBins::CentroidBins(const std::vector<Eigen::Vector3d>& centroids, const Eigen::Vector3d& period, double radius)
    : period_(period) {
  if (!(radius > 0)) throw std::invalid_argument("CentroidBins: the radius must be positive");
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  if (!centroids.empty()) lo = hi = centroids.front();
  for (const Eigen::Vector3d& c : centroids) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  for (int d = 0; d < 3; ++d) {
    const bool periodic = period_[d] > 0;
    origin_[d] = periodic ? 0.0 : lo[d];
    const double extent = periodic ? period_[d] : hi[d] - lo[d];
    count_[d] = std::max(1L, static_cast<long>(std::floor(extent / radius)));
    width_[d] = std::max(extent / count_[d], radius);
  }
  const long bins = count_[0] * count_[1] * count_[2];
  std::vector<long> bin(centroids.size());
  start_.assign(bins + 1, 0);
  for (std::size_t t = 0; t < centroids.size(); ++t) {
    long b = 0;
    for (int d = 0; d < 3; ++d) b = b * count_[d] + std::clamp(bin_of(d, centroids[t][d]), 0L, count_[d] - 1);
    bin[t] = b;
    ++start_[b + 1];
  }
  for (long b = 0; b < bins; ++b) start_[b + 1] += start_[b];
  indices_.resize(centroids.size());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t t = 0; t < centroids.size(); ++t) indices_[fill[bin[t]]++] = static_cast<int>(t);
}

long CentroidBins::bin_of(int d, double v) const {
  if (period_[d] > 0) v -= period_[d] * std::floor(v / period_[d]);
  return static_cast<long>(std::floor((v - origin_[d]) / width_[d]));
}

void CentroidBins::candidates(const Eigen::Vector3d& x, std::vector<int>& out) const {
  out.clear();
  std::array<std::vector<long>, 3> range;  // the bins to visit along each axis, distinct
  for (int d = 0; d < 3; ++d) {
    const long i = bin_of(d, x[d]);
    for (long k = i - 1; k <= i + 1; ++k) {
      if (period_[d] > 0) {
        const long w = ((k % count_[d]) + count_[d]) % count_[d];
        if (std::find(range[d].begin(), range[d].end(), w) == range[d].end()) range[d].push_back(w);
      } else if (k >= 0 && k < count_[d]) {
        range[d].push_back(k);
      }
    }
  }
  for (long i : range[0])
    for (long j : range[1])
      for (long k : range[2]) {
        const long b = (i * count_[1] + j) * count_[2] + k;
        out.insert(out.end(), indices_.begin() + start_[b], indices_.begin() + start_[b + 1]);
      }
  std::sort(out.begin(), out.end());
}

}  // namespace rbcflow
