#include "near_field.h"

#include <omp.h>

#include <Eigen/Geometry>
#include <map>
#include <vector>

#include "centroid_bins.h"
#include "libsolver/kernels/stokes_kernels.h"
#include "triangle_rules.h"

namespace rbcflow {

namespace {

constexpr int kDuffyPoints = 16;
constexpr int kMaxDepth = 7;
constexpr double kSubdivideFactor = 3.0;
constexpr double kCoincident = 1e-12;  // relative distance of a target "at" a Gauss point

// Adds rule-weighted sum over the sub-triangle whose vertices, in barycentric coordinates of
// the element v, are the columns of b.
void add_rule(const Eigen::Matrix3d& v, const Eigen::Matrix3d& b, const Eigen::Vector3d& x,
              const TriangleRule& rule, double area, Eigen::Matrix<double, 3, 9>& out,
              int* coincident_point = nullptr) {
  for (int q = 0; q < rule.weights.size(); ++q) {
    const Eigen::Vector3d lambda = b * rule.barycentric.row(q).transpose();
    const Eigen::Vector3d r = v * lambda - x;
    if (coincident_point && r.norm() <= kCoincident * std::sqrt(area)) {
      *coincident_point = q;
      continue;
    }
    const Eigen::Matrix3d g = (rule.weights[q] * area) * stokeslet(r);
    for (int a = 0; a < 3; ++a) out.block<3, 3>(0, 3 * a) += lambda[a] * g;
  }
}

double area_of(const Eigen::Matrix3d& p) {
  return 0.5 * (p.col(1) - p.col(0)).cross(p.col(2) - p.col(0)).norm();
}

void subdivide(const Eigen::Matrix3d& v, const Eigen::Matrix3d& b, const Eigen::Vector3d& x,
               int depth, Eigen::Matrix<double, 3, 9>& out) {
  const Eigen::Matrix3d p = v * b;
  const double diameter = std::max({(p.col(1) - p.col(0)).norm(), (p.col(2) - p.col(1)).norm(),
                                    (p.col(0) - p.col(2)).norm()});
  if (depth == kMaxDepth || (p.rowwise().mean() - x).norm() > kSubdivideFactor * diameter) {
    add_rule(v, b, x, gauss7_rule(), area_of(p), out);
    return;
  }
  Eigen::Matrix3d m;  // edge midpoints (barycentric)
  for (int a = 0; a < 3; ++a) m.col(a) = 0.5 * (b.col(a) + b.col((a + 1) % 3));
  Eigen::Matrix3d child;
  for (int a = 0; a < 3; ++a) {
    child << b.col(a), m.col(a), m.col((a + 2) % 3);
    subdivide(v, child, x, depth + 1, out);
  }
  subdivide(v, m, x, depth + 1, out);
}

}  // namespace

Eigen::Matrix<double, 3, 9> element_single_layer(const Eigen::Matrix3d& v, const Eigen::Vector3d& x) {
  Eigen::Matrix<double, 3, 9> out = Eigen::Matrix<double, 3, 9>::Zero();
  const Eigen::Vector3d e1 = v.col(1) - v.col(0), e2 = v.col(2) - v.col(0);
  const Eigen::Vector3d normal = e1.cross(e2);
  const double twice_area = normal.norm();
  const double diameter = std::max({e1.norm(), e2.norm(), (v.col(2) - v.col(1)).norm()});
  const Eigen::Vector3d d = x - v.col(0);
  const double height = d.dot(normal) / twice_area;
  // Barycentric coordinates of the projection of x.
  const Eigen::Vector3d in_plane = d - height * normal / twice_area;
  const double l1 = in_plane.cross(e2).dot(normal) / (twice_area * twice_area);
  const double l2 = e1.cross(in_plane).dot(normal) / (twice_area * twice_area);
  const Eigen::Vector3d lambda(1.0 - l1 - l2, l1, l2);
  const double eps = 1e-10;
  if (std::abs(height) <= eps * diameter && lambda.minCoeff() >= -eps) {
    // Split at x into three triangles with x as their vertex 0; Duffy's rule on each.
    static thread_local const TriangleRule duffy = duffy_rule(kDuffyPoints);
    for (int a = 0; a < 3; ++a) {
      Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
      b.col(0) = lambda;
      b((a + 1) % 3, 1) = 1.0;
      b((a + 2) % 3, 2) = 1.0;
      const double sub_area = area_of(v * b);
      if (sub_area > eps * eps * diameter * diameter) add_rule(v, b, x, duffy, sub_area, out);
    }
    return out;
  }
  subdivide(v, Eigen::Matrix3d::Identity(), x, 0, out);
  return out;
}

NearField near_field(const WallElements& e, const Eigen::Matrix<double, Eigen::Dynamic, 3>& targets,
                     double near_factor, double preconditioner_factor, const std::function<bool(int)>& rows) {
  using Triplet = Eigen::Triplet<double>;
  using Blocks = std::map<int, Eigen::Matrix3d>;  // node -> 3 x 3 block of one target's row
  const int nt = static_cast<int>(targets.rows());
  const TriangleRule& gauss = gauss7_rule();
  const int threads = omp_get_max_threads();
  std::vector<std::vector<Triplet>> correction(threads), local(threads);
  std::vector<std::vector<std::pair<int, int>>> coincident(threads);
  auto emit = [](int i, const Blocks& blocks, std::vector<Triplet>& out) {
    for (const auto& [node, b] : blocks)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) out.emplace_back(3 * i + k, 3 * node + l, b(k, l));
  };
  std::vector<Eigen::Vector3d> centroids(e.num_triangles());
  for (int t = 0; t < e.num_triangles(); ++t) centroids[t] = e.vertices[t].rowwise().mean();
  const double max_diameter = e.num_triangles() > 0 ? e.diameters.maxCoeff() : 1.0;
  const CentroidBins bins(centroids, e.wall.period, near_factor * max_diameter);
#pragma omp parallel for schedule(dynamic, 16)
  for (int i = 0; i < nt; ++i) {
    const int thread = omp_get_thread_num();
    const Eigen::Vector3d x = targets.row(i).transpose();
    const bool wanted = !rows || rows(i);
    Blocks cor, loc;
    std::vector<int> near_triangles;
    bins.candidates(x, near_triangles);
    for (const int t : near_triangles) {
      const Eigen::Vector3d& c = centroids[t];
      const Eigen::Vector3d r = minimum_image(c - x, e.wall.period);
      if (r.norm() >= near_factor * e.diameters[t]) continue;
      const Eigen::Matrix3d v = e.vertices[t].colwise() + (r - (c - x));  // the image next to x
      Eigen::Matrix<double, 3, 9> smooth = Eigen::Matrix<double, 3, 9>::Zero();
      int q = -1;
      add_rule(v, Eigen::Matrix3d::Identity(), x, gauss, e.areas[t], smooth, &q);
      if (q >= 0) coincident[thread].emplace_back(i, 7 * t + q);
      if (!wanted) continue;
      const Eigen::Matrix<double, 3, 9> exact = element_single_layer(v, x);
      const bool in_preconditioner = r.norm() < preconditioner_factor * e.diameters[t];
      for (int a = 0; a < 3; ++a) {
        const int node = e.wall.surface.triangles(t, a);
        auto [it, fresh] = cor.try_emplace(node, Eigen::Matrix3d::Zero());
        it->second += exact.block<3, 3>(0, 3 * a) - smooth.block<3, 3>(0, 3 * a);
        if (!in_preconditioner) continue;
        auto [jt, fresh_local] = loc.try_emplace(node, Eigen::Matrix3d::Zero());
        jt->second += exact.block<3, 3>(0, 3 * a);
      }
    }
    emit(i, cor, correction[thread]);
    emit(i, loc, local[thread]);
  }
  NearField out;
  auto assemble = [&](std::vector<std::vector<Triplet>>& parts, Eigen::SparseMatrix<double>& m) {
    std::vector<Triplet> all;
    for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
    m.resize(3 * nt, 3 * e.num_nodes());
    m.setFromTriplets(all.begin(), all.end());
  };
  assemble(correction, out.correction);
  assemble(local, out.local);
  for (const auto& c : coincident) out.coincident.insert(out.coincident.end(), c.begin(), c.end());
  return out;
}

}  // namespace rbcflow
