#include "geometry/vessel/mesh_orientation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <queue>
#include <utility>
#include <vector>

namespace rbcflow {

namespace {

// lumen_flux of the triangles listed (all when `only` is empty).
double flux(const VesselMesh& wall, const std::vector<int>& only) {
  const int n = only.empty() ? wall.surface.num_triangles() : static_cast<int>(only.size());
  const Eigen::Vector3d x0 = wall.surface.points.row(0).transpose();
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Matrix3d v = triangle_vertices(wall, only.empty() ? k : only[k]);
    Eigen::Vector3d c = v.rowwise().mean() - x0;
    for (int d = 0; d < 3; ++d)
      if (wall.period[d] > 0) c[d] = 0;
    // A n = (p1 - p0) x (p2 - p0) / 2
    sum += 0.5 * (v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).dot(c);
  }
  return sum;
}

void flip(Eigen::Matrix<int, Eigen::Dynamic, 3>& triangles, int t) {
  std::swap(triangles(t, 1), triangles(t, 2));
}

}  // namespace

double lumen_flux(const VesselMesh& wall) { return flux(wall, {}); }

void orient_into_lumen(VesselMesh& wall) {
  auto& tri = wall.surface.triangles;
  const int n = wall.surface.num_triangles();
  std::map<std::pair<int, int>, std::vector<int>> edge_triangles;
  for (int t = 0; t < n; ++t)
    for (int a = 0; a < 3; ++a) {
      const int i = tri(t, a), j = tri(t, (a + 1) % 3);
      edge_triangles[{std::min(i, j), std::max(i, j)}].push_back(t);
    }
  // Whether triangle t traverses the edge i -> j.
  auto forward = [&](int t, int i, int j) {
    for (int a = 0; a < 3; ++a)
      if (tri(t, a) == i && tri(t, (a + 1) % 3) == j) return true;
    return false;
  };
  std::vector<bool> seen(n, false);
  for (int seed = 0; seed < n; ++seed) {
    if (seen[seed]) continue;
    std::vector<int> piece{seed};
    std::queue<int> front;
    front.push(seed);
    seen[seed] = true;
    while (!front.empty()) {
      const int t = front.front();
      front.pop();
      for (int a = 0; a < 3; ++a) {
        const int i = tri(t, a), j = tri(t, (a + 1) % 3);
        const auto& shared = edge_triangles[{std::min(i, j), std::max(i, j)}];
        if (shared.size() != 2) continue;
        const int u = shared[0] == t ? shared[1] : shared[0];
        if (seen[u]) continue;
        if (forward(u, i, j)) flip(tri, u);  // a neighbour must traverse the edge j -> i
        seen[u] = true;
        piece.push_back(u);
        front.push(u);
      }
    }
    if (flux(wall, piece) > 0)
      for (int t : piece) flip(tri, t);
  }
}

}  // namespace rbcflow
