#include "real_space_sum.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "libsolver/common/memory_report.h"
#include "libsolver/kernels/ewald_real_kernel.h"

namespace rbcflow {
namespace {

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
  // The weight of sorted source s at squared distance r2 (its other images keep weight 1).
  double weight(int s, double r2, const std::vector<double>& work) const {
    return r2 < nearest_image2_ ? 1.0 - work[s] : 1.0;
  }

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


// u.row(t) = sum over the pairs (i, s, r) of target t of term(i, s, r, weight), parallel over
// the targets; weight(r2) is the pair's 1 - share (1 when the target shares no pair).
template <class Term>
PointField sum_over_pairs(const NeighborList& pairs, const ShareLookup& lookup, Term&& term) {
  PointField u(pairs.n_targets(), 3);
#pragma omp parallel
  {
    std::vector<double> work = lookup.work(pairs);
#pragma omp for schedule(dynamic, 64)
    for (int k = 0; k < pairs.n_targets(); ++k) {
      const int t = pairs.target_order()[k];
      const bool weighted = lookup.scatter(t, work);
      Eigen::Vector3d acc = Eigen::Vector3d::Zero();
      pairs.for_each_pair(t, [&](std::int64_t i, int s, const Eigen::Vector3d& r) {
        acc += term(i, s, r, [&](double r2) { return weighted ? lookup.weight(s, r2, work) : 1.0; });
      });
      if (weighted) lookup.clear(t, work);
      u.row(t) = acc.transpose();
    }
  }
  return u;
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
  check_rows(forces, pairs.n_sources(), "the force field");
  const std::vector<double> f = sorted_densities(pairs, {&forces});
  const EwaldRealKernel kernel(xi);
  const bool fill = prepare(pairs, coefficients);
  double* c = coefficients ? coefficients->data() : nullptr;
  const bool compute = !c || fill;
  const ShareLookup lookup(pairs, compute ? shares : nullptr);
  return sum_over_pairs(pairs, lookup, [&](std::int64_t i, int s, const Eigen::Vector3d& r, auto&& weight) {
    const Eigen::Map<const Eigen::Vector3d> fs(&f[3 * static_cast<std::size_t>(s)]);
    double a, b;  // S^R f = a f + b (r.f) r
    if (!compute) {
      a = c[2 * i];
      b = c[2 * i + 1];
    } else {
      const double r2 = r.squaredNorm(), rn = std::sqrt(r2);
      const StokesletSplitCoeffs k2 = kernel.stokeslet_coeffs(rn);
      const double w = weight(r2);
      a = w * k2.a;
      b = w * k2.b / r2;
      if (c) {
        c[2 * i] = a;
        c[2 * i + 1] = b;
      }
    }
    return Eigen::Vector3d(a * fs + (b * r.dot(fs)) * r);
  });
}

PointField real_space_double_layer(const NeighborList& pairs, double xi, const PointField& q,
                                   const PointField& normals, std::vector<double>* coefficients,
                                   const PairShares* shares) {
  check_rows(q, pairs.n_sources(), "the double-layer density");
  check_rows(normals, pairs.n_sources(), "the normal field");
  const std::vector<double> qn = sorted_densities(pairs, {&q, &normals});
  const EwaldRealKernel kernel(xi);
  const bool fill = prepare(pairs, coefficients);
  double* c = coefficients ? coefficients->data() : nullptr;
  const bool compute = !c || fill;
  const ShareLookup lookup(pairs, compute ? shares : nullptr);
  return sum_over_pairs(pairs, lookup, [&](std::int64_t i, int s, const Eigen::Vector3d& r, auto&& weight) {
    const Eigen::Map<const Eigen::Vector3d> qs(&qn[6 * static_cast<std::size_t>(s)]);
    const Eigen::Map<const Eigen::Vector3d> ns(&qn[6 * static_cast<std::size_t>(s) + 3]);
    double alpha, beta;
    if (!compute) {
      alpha = c[2 * i];
      beta = c[2 * i + 1];
    } else {
      const double r2 = r.squaredNorm();
      const StressletSplitCoeffs k2 = kernel.stresslet_coeffs(std::sqrt(r2));
      const double w = weight(r2);
      alpha = w * k2.alpha;
      beta = w * k2.beta;
      if (c) {
        c[2 * i] = alpha;
        c[2 * i + 1] = beta;
      }
    }
    const double rq = r.dot(qs), rn = r.dot(ns);
    return Eigen::Vector3d((alpha * rq * rn + beta * qs.dot(ns)) * r + beta * (rn * qs + rq * ns));
  });
}

}  // namespace rbcflow
