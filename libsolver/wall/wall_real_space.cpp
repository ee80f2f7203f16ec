#include "wall_real_space.h"

#include <omp.h>

#include <algorithm>
#include <vector>

#include "libsolver/kernels/ewald_real_kernel.h"
#include "triangle_rules.h"

namespace rbcflow {

Eigen::SparseMatrix<double> wall_real_space_matrix(const WallElements& e, const NeighborList& pairs, double xi) {
  using Triplet = Eigen::Triplet<double>;
  const EwaldRealKernel kernel(xi);
  const TriangleRule& rule = gauss7_rule();
  const std::vector<int>& order = pairs.order();
  const int nt = pairs.n_targets();
  std::vector<std::vector<Triplet>> parts(omp_get_max_threads());
#pragma omp parallel
  {
    std::vector<Eigen::Matrix3d> blocks(e.num_nodes(), Eigen::Matrix3d::Zero());
    std::vector<char> seen(e.num_nodes(), 0);
    std::vector<int> touched;
    std::vector<Triplet>& out = parts[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 16)
    for (int t = 0; t < nt; ++t) {
      pairs.for_each_neighbor(t, [&](int s, const Eigen::Vector3d& r) {
        const int q = order[s], triangle = q / 7, point = q % 7;
        const Eigen::Matrix3d g = e.weights[q] * kernel.stokeslet_matrix(r);
        for (int a = 0; a < 3; ++a) {
          const int node = e.wall.surface.triangles(triangle, a);
          if (!seen[node]) {
            seen[node] = 1;
            touched.push_back(node);
          }
          blocks[node] += rule.barycentric(point, a) * g;
        }
      });
      std::sort(touched.begin(), touched.end());
      for (const int node : touched) {
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) out.emplace_back(3 * t + k, 3 * node + l, blocks[node](k, l));
        blocks[node].setZero();
        seen[node] = 0;
      }
      touched.clear();
    }
  }
  std::vector<Triplet> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  Eigen::SparseMatrix<double> m(3 * nt, 3 * e.num_nodes());
  m.setFromTriplets(all.begin(), all.end());
  return m;
}

}  // namespace rbcflow
