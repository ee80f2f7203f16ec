#include "real_space_sum.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "libsolver/common/memory_report.h"
#include "libsolver/kernels/ewald_real_batch.h"

namespace rbcflow {
namespace {

void check_xi(double xi) {
  if (!(xi > 0.0)) throw std::invalid_argument("real-space Ewald sum: xi must be positive, got " + std::to_string(xi));
}

void check_rows(const PointField& field, int n, const char* what) {
  if (field.rows() != n)
    throw std::invalid_argument(std::string("real-space Ewald sum: ") + what + " has " +
                                std::to_string(field.rows()) + " rows for " + std::to_string(n) +
                                " sources");
}

// Densities gathered into the neighbour list's sorted source order, `width` numbers per source.
std::vector<double> sorted_densities(const NeighborList& pairs,
                                     std::initializer_list<const PointField*> fields) {
  const int width = 3 * static_cast<int>(fields.size());
  std::vector<double> out(static_cast<std::size_t>(width) * pairs.n_sources());
  const std::vector<int>& order = pairs.order();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < pairs.n_sources(); ++i) {
    double* o = &out[static_cast<std::size_t>(width) * i];
    for (const PointField* f : fields)
      for (int d = 0; d < 3; ++d) *o++ = (*f)(order[i], d);
  }
  return out;
}

// Two coefficients per pair in `coefficients` (filled now when it is empty, else read).
bool prepare(const NeighborList& pairs, std::vector<double>* coefficients) {
  if (!coefficients) return false;
  const bool fill = coefficients->empty();
  if (fill) coefficients->resize(2 * static_cast<std::size_t>(pairs.n_pairs()));
  return fill;
}

// PairShares in the neighbour list's sorted source order: a thread scatters the shares of its
// current target into a work array (one number per source) so that each pair finds its own.
class ShareLookup {
 public:
  ShareLookup(const NeighborList& pairs, const PairShares* shares)
      : shares_(shares && !shares->offsets.empty() ? shares : nullptr) {
    if (!shares_) return;
    const auto n_segments = static_cast<std::int64_t>(shares_->segments.size());
    if (shares_->offsets.size() != static_cast<std::size_t>(pairs.n_targets()) + 1 || shares_->offsets.front() != 0 ||
        shares_->offsets.back() != n_segments)
      throw std::invalid_argument("real-space Ewald sum: the pair shares do not fit the " +
                                  std::to_string(pairs.n_targets()) + " targets");
    rank_.resize(pairs.n_sources());
    for (int i = 0; i < pairs.n_sources(); ++i) rank_[pairs.order()[i]] = i;
    for (const PairShares::Segment& g : shares_->segments)
      for (int e = 0; e < g.count; ++e) {
        const int s = g.first_source + g.nodes[e].node();
        if (s < 0 || s >= pairs.n_sources())
          throw std::invalid_argument("real-space Ewald sum: a pair share names source " + std::to_string(s) + " of " +
                                      std::to_string(pairs.n_sources()));
      }
    const double half_side = 0.5 * pairs.box().lengths().minCoeff();
    nearest_image2_ = half_side * half_side;
  }

  // A work array for one thread (empty without shares).
  std::vector<double> work(const NeighborList& pairs) const {
    return std::vector<double>(shares_ ? pairs.n_sources() : 0, 0.0);
  }
  // Adds target t's shares to `work`; false when it has none.
  bool scatter(int t, std::vector<double>& work) const {
    if (!shares_ || shares_->offsets[t] == shares_->offsets[t + 1]) return false;
    for_each_share(t, [&](int s, float eta) { work[rank_[s]] += eta; });
    return true;
  }
  void clear(int t, std::vector<double>& work) const {
    for_each_share(t, [&](int s, float) { work[rank_[s]] = 0.0; });
  }
  // Squared distances below which a pair is at its nearest image (its other images keep weight 1).
  double nearest_image2() const { return nearest_image2_; }

 private:
  template <class F>
  void for_each_share(int t, F&& f) const {
    for (std::int64_t i = shares_->offsets[t]; i < shares_->offsets[t + 1]; ++i) {
      const PairShares::Segment& g = shares_->segments[i];
      for (int e = 0; e < g.count; ++e) f(g.first_source + g.nodes[e].node(), g.nodes[e].eta());
    }
  }

  const PairShares* shares_;
  std::vector<int> rank_;  // caller's source index -> sorted
  double nearest_image2_ = 0.0;
};


// The pairs of one target, a chunk at a time: their separations, weights and sources' densities
// in arrays, so that the kernels and terms of a chunk are evaluated together, 4 pairs an
// instruction (ewald_real_batch.h). The pairs of a target have consecutive indices from `first`.
struct PairChunk {
  static constexpr int kSize = 64;
  alignas(32) double x[kSize], y[kSize], z[kSize];
  alignas(32) double a[kSize], b[kSize];  // the pair's two radial coefficients
  alignas(32) double eta[kSize];          // its share (0 when the target shares no pair)
  alignas(32) double density[6][kSize];   // its source's density components (f, or q and n)
  std::int64_t first = 0;
  int n = 0;
};

// u.row(t) = sum over the chunks of target t's pairs of flush(chunk, weighted), which returns
// the chunk's sum (weighted: the target shares pairs, whose shares are in chunk.eta); parallel
// over the targets. `densities`: `Width` numbers per sorted source (sorted_densities).
template <int Width, class Flush>
PointField sum_over_pairs(const NeighborList& pairs, const ShareLookup& lookup, const std::vector<double>& densities,
                          Flush&& flush) {
  PointField u(pairs.n_targets(), 3);
#pragma omp parallel
  {
    std::vector<double> work = lookup.work(pairs);
    PairChunk chunk;
#pragma omp for schedule(dynamic, 64)
    for (int k = 0; k < pairs.n_targets(); ++k) {
      const int t = pairs.target_order()[k];
      const bool weighted = lookup.scatter(t, work);
      Eigen::Vector3d acc = Eigen::Vector3d::Zero();
      chunk.n = 0;
      pairs.for_each_pair(t, [&](std::int64_t i, int s, const Eigen::Vector3d& r) {
        if (chunk.n == 0) chunk.first = i;
        const int j = chunk.n++;
        chunk.x[j] = r.x();
        chunk.y[j] = r.y();
        chunk.z[j] = r.z();
        const double* d = &densities[Width * static_cast<std::size_t>(s)];
        for (int m = 0; m < Width; ++m) chunk.density[m][j] = d[m];
        chunk.eta[j] = weighted ? work[s] : 0.0;
        if (chunk.n == PairChunk::kSize) {
          acc += flush(chunk, weighted);
          chunk.n = 0;
        }
      });
      if (chunk.n > 0) acc += flush(chunk, weighted);
      if (weighted) lookup.clear(t, work);
      u.row(t) = acc.transpose();
    }
  }
  return u;
}

// The chunk's coefficients: computed by `compute(chunk)` and weighted (stored in `c` when it
// is being filled), or read from the kept coefficients `c`.
template <class Compute>
void chunk_coefficients(PairChunk& chunk, bool weighted, double nearest_image2, double* c, bool compute_them,
                        Compute&& compute) {
  const int n = chunk.n;
  if (!compute_them) {
    const double* k = c + 2 * chunk.first;
#pragma omp simd
    for (int j = 0; j < n; ++j) {
      chunk.a[j] = k[2 * j];
      chunk.b[j] = k[2 * j + 1];
    }
    return;
  }
  compute(chunk);
  if (weighted) {
    // A pair is weighted at its nearest image only (PairShares).
#pragma omp simd
    for (int j = 0; j < n; ++j) {
      const double r2 = chunk.x[j] * chunk.x[j] + chunk.y[j] * chunk.y[j] + chunk.z[j] * chunk.z[j];
      const double w = r2 < nearest_image2 ? 1.0 - chunk.eta[j] : 1.0;
      chunk.a[j] *= w;
      chunk.b[j] *= w;
    }
  }
  if (c) {
    double* k = c + 2 * chunk.first;
    for (int j = 0; j < n; ++j) {
      k[2 * j] = chunk.a[j];
      k[2 * j + 1] = chunk.b[j];
    }
  }
}

}  // namespace

PairShares PairShares::from_lists(std::vector<std::int64_t> offsets, const std::vector<int>& sources,
                                  const std::vector<float>& shares) {
  if (sources.size() != shares.size() || (!offsets.empty() && (offsets.front() != 0 ||
                                                               offsets.back() != static_cast<std::int64_t>(sources.size()))))
    throw std::invalid_argument("pair shares: " + std::to_string(sources.size()) + " sources, " +
                                std::to_string(shares.size()) + " shares and offsets that do not fit them");
  // Each target's entries in segments whose sources lie within PatchNode::kMaxNodes above the
  // segment's first.
  PairShares p;
  p.held.reserve(sources.size());
  p.offsets.assign(offsets.size(), 0);
  for (std::size_t t = 0; t + 1 < offsets.size(); ++t) {
    p.offsets[t + 1] = p.offsets[t];
    for (std::int64_t i = offsets[t]; i < offsets[t + 1];) {
      const int first = sources[i];
      std::int64_t j = i;
      for (; j < offsets[t + 1] && sources[j] >= first && sources[j] - first < PatchNode::kMaxNodes; ++j)
        p.held.emplace_back(sources[j] - first, shares[j]);
      p.segments.push_back({p.held.data() + i, static_cast<std::int32_t>(j - i), first});
      ++p.offsets[t + 1];
      i = j;
    }
  }
  return p;
}

std::size_t PairShares::memory_bytes() const { return heap_bytes(offsets) + heap_bytes(segments) + heap_bytes(held); }

double pair_share_radius(const PeriodicBox& box, double cutoff) {
  return (1.0 - 1e-9) * std::min(cutoff, 0.5 * box.lengths().minCoeff());
}

PointField real_space_single_layer(const NeighborList& pairs, double xi, const PointField& forces,
                                   std::vector<double>* coefficients, const PairShares* shares) {
  check_xi(xi);
  check_rows(forces, pairs.n_sources(), "the force field");
  const std::vector<double> f = sorted_densities(pairs, {&forces});
  const bool fill = prepare(pairs, coefficients);
  double* c = coefficients ? coefficients->data() : nullptr;
  const bool compute = !c || fill;
  const ShareLookup lookup(pairs, compute ? shares : nullptr);
  return sum_over_pairs<3>(pairs, lookup, f, [&](PairChunk& chunk, bool weighted) {
    chunk_coefficients(chunk, weighted, lookup.nearest_image2(), c, compute, [&](PairChunk& k) {
      batch_stokeslet_coeffs(xi, k.x, k.y, k.z, k.n, k.a, k.b);
    });
    // S^R f = a f + b (r.f) r
    const double *fx = chunk.density[0], *fy = chunk.density[1], *fz = chunk.density[2];
    double ux = 0, uy = 0, uz = 0;
#pragma omp simd reduction(+ : ux, uy, uz)
    for (int j = 0; j < chunk.n; ++j) {
      const double rx = chunk.x[j], ry = chunk.y[j], rz = chunk.z[j];
      const double brf = chunk.b[j] * (rx * fx[j] + ry * fy[j] + rz * fz[j]), a = chunk.a[j];
      ux += a * fx[j] + brf * rx;
      uy += a * fy[j] + brf * ry;
      uz += a * fz[j] + brf * rz;
    }
    return Eigen::Vector3d(ux, uy, uz);
  });
}

PointField real_space_double_layer(const NeighborList& pairs, double xi, const PointField& q,
                                   const PointField& normals, std::vector<double>* coefficients,
                                   const PairShares* shares) {
  check_xi(xi);
  check_rows(q, pairs.n_sources(), "the double-layer density");
  check_rows(normals, pairs.n_sources(), "the normal field");
  const std::vector<double> qn = sorted_densities(pairs, {&q, &normals});
  const bool fill = prepare(pairs, coefficients);
  double* c = coefficients ? coefficients->data() : nullptr;
  const bool compute = !c || fill;
  const ShareLookup lookup(pairs, compute ? shares : nullptr);
  return sum_over_pairs<6>(pairs, lookup, qn, [&](PairChunk& chunk, bool weighted) {
    chunk_coefficients(chunk, weighted, lookup.nearest_image2(), c, compute, [&](PairChunk& k) {
      batch_stresslet_coeffs(xi, k.x, k.y, k.z, k.n, k.a, k.b);
    });
    // T^R q n = (alpha (r.q)(r.n) + beta q.n) r + beta ((r.n) q + (r.q) n)
    const double *qx = chunk.density[0], *qy = chunk.density[1], *qz = chunk.density[2];
    const double *nx = chunk.density[3], *ny = chunk.density[4], *nz = chunk.density[5];
    double ux = 0, uy = 0, uz = 0;
#pragma omp simd reduction(+ : ux, uy, uz)
    for (int j = 0; j < chunk.n; ++j) {
      const double rx = chunk.x[j], ry = chunk.y[j], rz = chunk.z[j];
      const double rq = rx * qx[j] + ry * qy[j] + rz * qz[j], rn = rx * nx[j] + ry * ny[j] + rz * nz[j];
      const double alpha = chunk.a[j], beta = chunk.b[j];
      const double radial = alpha * rq * rn + beta * (qx[j] * nx[j] + qy[j] * ny[j] + qz[j] * nz[j]);
      ux += radial * rx + beta * (rn * qx[j] + rq * nx[j]);
      uy += radial * ry + beta * (rn * qy[j] + rq * ny[j]);
      uz += radial * rz + beta * (rn * qz[j] + rq * nz[j]);
    }
    return Eigen::Vector3d(ux, uy, uz);
  });
}

}  // namespace rbcflow
