#include "neighbor_list.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "libsolver/common/memory_report.h"

namespace rbcflow {
namespace {

// The cells: nc_d per direction of side at least cutoff / 2, at most about 4 per source.
struct CellGrid {
  std::array<int, 3> n{};       // cells per direction
  std::array<int, 3> reach{};   // neighbour cells to visit on each side: ceil(cutoff / side)
  std::array<int, 3> images{};  // lattice vectors n_d in [-images, images]
  Eigen::Vector3d side;

  CellGrid(const PeriodicBox& box, double cutoff, int n_sources) {
    const double max_cells = std::max(64.0, 4.0 * n_sources);
    Eigen::Vector3d count;
    for (int d = 0; d < 3; ++d) count[d] = std::max(1.0, std::floor(2.0 * box.length(d) / cutoff));
    const double scale = std::cbrt(std::min(1.0, max_cells / count.prod()));
    for (int d = 0; d < 3; ++d) {
      n[d] = std::max(1, static_cast<int>(std::floor(count[d] * scale)));
      side[d] = box.length(d) / n[d];
      reach[d] = static_cast<int>(std::ceil(cutoff / side[d]));
      images[d] = (reach[d] + n[d] - 1) / n[d];  // ceil(reach / n)
    }
  }

  int cell_of(const Eigen::Vector3d& x, int d) const {
    return std::min(n[d] - 1, static_cast<int>(x[d] / side[d]));
  }
  int image_id(int n0, int n1, int n2) const {
    return ((n0 + images[0]) * (2 * images[1] + 1) + (n1 + images[1])) * (2 * images[2] + 1) +
           (n2 + images[2]);
  }
  int image_count() const {
    return (2 * images[0] + 1) * (2 * images[1] + 1) * (2 * images[2] + 1);
  }
};

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

NeighborList::NeighborList(const PeriodicBox& box, double cutoff, const PointField& sources,
                           const PointField& targets)
    : box_(box), cutoff_(cutoff), coincidence_(1e-12 * std::cbrt(box.volume())) {
  if (!(std::isfinite(cutoff) && cutoff > 0.0))
    throw std::invalid_argument("neighbour list: the cutoff must be positive, got " +
                                std::to_string(cutoff));
  if (cutoff > 16.0 * box.lengths().maxCoeff())
    throw std::invalid_argument("neighbour list: the cutoff " + std::to_string(cutoff) +
                                " exceeds 16 box lengths");
  const int ns = static_cast<int>(sources.rows()), nt = static_cast<int>(targets.rows());
  const CellGrid cells(box, cutoff, ns);
  const int n_cells = cells.n[0] * cells.n[1] * cells.n[2];

  // Image table.
  image_shifts_.resize(3 * static_cast<std::size_t>(cells.image_count()));
  for (int a = -cells.images[0]; a <= cells.images[0]; ++a)
    for (int b = -cells.images[1]; b <= cells.images[1]; ++b)
      for (int c = -cells.images[2]; c <= cells.images[2]; ++c) {
        double* s = &image_shifts_[3 * static_cast<std::size_t>(cells.image_id(a, b, c))];
        s[0] = a * box.length(0);
        s[1] = b * box.length(1);
        s[2] = c * box.length(2);
      }

  // Sources sorted by cell (counting sort).
  std::vector<int> cell(ns);
  std::vector<Eigen::Vector3d> wrapped(ns);
  std::vector<int> cell_start(n_cells + 1, 0);
  for (int s = 0; s < ns; ++s) {
    wrapped[s] = box.wrap(sources.row(s).transpose());
    cell[s] =
        (cells.cell_of(wrapped[s], 0) * cells.n[1] + cells.cell_of(wrapped[s], 1)) * cells.n[2] +
        cells.cell_of(wrapped[s], 2);
    ++cell_start[cell[s] + 1];
  }
  for (int c = 0; c < n_cells; ++c) cell_start[c + 1] += cell_start[c];
  order_.resize(ns);
  sources_.resize(3 * static_cast<std::size_t>(ns));
  {
    std::vector<int> next(cell_start.begin(), cell_start.end() - 1);
    for (int s = 0; s < ns; ++s) {
      const int i = next[cell[s]]++;
      order_[i] = s;
      for (int d = 0; d < 3; ++d) sources_[3 * static_cast<std::size_t>(i) + d] = wrapped[s][d];
    }
  }
  // Targets sorted by cell as well, so that consecutive targets visit the same sources.
  std::vector<Eigen::Vector3d> wrapped_targets(nt);
  std::vector<int> target_cell(nt), target_start(n_cells + 1, 0);
  for (int t = 0; t < nt; ++t) {
    const Eigen::Vector3d& x = wrapped_targets[t] = box.wrap(targets.row(t).transpose());
    target_cell[t] =
        (cells.cell_of(x, 0) * cells.n[1] + cells.cell_of(x, 1)) * cells.n[2] + cells.cell_of(x, 2);
    ++target_start[target_cell[t] + 1];
  }
  for (int c = 0; c < n_cells; ++c) target_start[c + 1] += target_start[c];
  const std::vector<int> target_begin = target_start;  // sorted targets of cell c: [begin[c], begin[c + 1])
  target_order_.resize(nt);
  rank_.resize(nt);
  targets_.resize(3 * static_cast<std::size_t>(nt));
  for (int t = 0; t < nt; ++t) {
    const int i = target_start[target_cell[t]]++;
    target_order_[i] = t;
    rank_[t] = i;
    for (int d = 0; d < 3; ++d)
      targets_[3 * static_cast<std::size_t>(i) + d] = wrapped_targets[t][d];
  }

  // The targets of one cell share the cells they search: for each cell holding targets, the
  // sources of every cell (and image) within the cutoff of it are gathered once, shifted, into
  // a contiguous list that each of its targets scans. The pairs of a target come in the order
  // of a search cell by cell (offsets o0, o1, o2 ascending, sources in sorted order), and
  // skipping the cells that cannot hold a pair changes none of them.
  const double rc2 = cutoff * cutoff, eps2 = coincidence_ * coincidence_;
  const double skip2 = rc2 * (1.0 + 1e-10);  // a cell this far or farther holds no pair, whatever the rounding
  struct Candidates {
    std::vector<double> x, y, z;
    std::vector<int> source, image;
    void clear() {
      for (std::vector<double>* v : {&x, &y, &z}) v->clear();
      source.clear();
      image.clear();
    }
  };
  const auto gather = [&](int home_cell, Candidates& c) {
    c.clear();
    const std::array<int, 3> home{home_cell / (cells.n[1] * cells.n[2]), (home_cell / cells.n[2]) % cells.n[1],
                                  home_cell % cells.n[2]};
    // Squared distance along d between the home cell and the cell at offset o.
    const auto gap2 = [&](int d, int o) {
      const double g = (std::abs(o) - 1) * cells.side[d];
      return o != 0 && g > 0.0 ? g * g : 0.0;
    };
    for (int o0 = -cells.reach[0]; o0 <= cells.reach[0]; ++o0) {
      const int u0 = home[0] + o0, n0 = floor_div(u0, cells.n[0]), c0 = u0 - n0 * cells.n[0];
      const double g0 = gap2(0, o0);
      if (g0 >= skip2) continue;
      for (int o1 = -cells.reach[1]; o1 <= cells.reach[1]; ++o1) {
        const int u1 = home[1] + o1, n1 = floor_div(u1, cells.n[1]), c1 = u1 - n1 * cells.n[1];
        const double g01 = g0 + gap2(1, o1);
        if (g01 >= skip2) continue;
        for (int o2 = -cells.reach[2]; o2 <= cells.reach[2]; ++o2) {
          if (g01 + gap2(2, o2) >= skip2) continue;
          const int u2 = home[2] + o2, n2 = floor_div(u2, cells.n[2]), c2 = u2 - n2 * cells.n[2];
          const int cell_index = (c0 * cells.n[1] + c1) * cells.n[2] + c2;
          const int image = cells.image_id(n0, n1, n2);
          const double* shift = &image_shifts_[3 * static_cast<std::size_t>(image)];
          for (int i = cell_start[cell_index]; i < cell_start[cell_index + 1]; ++i) {
            const double* xs = &sources_[3 * static_cast<std::size_t>(i)];
            c.x.push_back(xs[0] + shift[0]);
            c.y.push_back(xs[1] + shift[1]);
            c.z.push_back(xs[2] + shift[2]);
            c.source.push_back(i);
            c.image.push_back(image);
          }
        }
      }
    }
  };
  // Runs emit(sorted target, candidate index, candidates) for every pair, a cell of targets
  // at a time (in parallel).
  const auto for_each_pair_by_cell = [&](auto&& emit) {
#pragma omp parallel
    {
      Candidates c;
#pragma omp for schedule(dynamic, 4)
      for (int home = 0; home < n_cells; ++home) {
        if (target_begin[home] == target_begin[home + 1]) continue;
        gather(home, c);
        const int m = static_cast<int>(c.source.size());
        for (int t = target_begin[home]; t < target_begin[home + 1]; ++t) {
          const double* xt = &targets_[3 * static_cast<std::size_t>(t)];
          emit(t, m, c, xt);
        }
      }
    }
  };

  // Whether a candidate is a pair is decided without branches (about half of them are not:
  // a branch per candidate mispredicts), the pairs compacted likewise.
  const auto is_pair = [rc2, eps2](const Candidates& c, int k, const double* xt) {
    const double r0 = c.x[k] - xt[0], r1 = c.y[k] - xt[1], r2 = c.z[k] - xt[2];
    const double d2 = r0 * r0 + r1 * r1 + r2 * r2;
    return static_cast<int>(d2 < rc2) & static_cast<int>(d2 > eps2);
  };
  const auto list_pairs = [&](int m, const Candidates& c, const double* xt, std::vector<int>& listed) {
    listed.resize(m + 1);
    int n = 0;
    for (int k = 0; k < m; ++k) {
      listed[n] = k;
      n += is_pair(c, k, xt);
    }
    return n;
  };
  // Codes the listed pairs (see codes_), out = nullptr only counts them; returns the words.
  home_image_ = cells.image_id(0, 0, 0);
  const auto code_pairs = [home = home_image_](const Candidates& c, const std::vector<int>& listed, int n,
                                               std::uint16_t* out) {
    std::int64_t words = 0;
    int previous = 0, image = home;
    for (int i = 0; i < n; ++i) {
      const int s = c.source[listed[i]], im = c.image[listed[i]];
      const std::int64_t step = static_cast<std::int64_t>(s) - previous;
      if (im == image && step > kEscape && step <= INT16_MAX) {
        if (out) out[words] = static_cast<std::uint16_t>(static_cast<std::int16_t>(step));
        ++words;
      } else {
        if (out) {
          out[words] = static_cast<std::uint16_t>(kEscape);
          out[words + 1] = static_cast<std::uint16_t>(static_cast<std::uint32_t>(s) & 0xffffu);
          out[words + 2] = static_cast<std::uint16_t>(static_cast<std::uint32_t>(s) >> 16);
          out[words + 3] = static_cast<std::uint16_t>(im);
        }
        words += 4;
        image = im;
      }
      previous = s;
    }
    return words;
  };
  offsets_.assign(nt + 1, 0);
  code_offsets_.assign(nt + 1, 0);
  for_each_pair_by_cell([&](int t, int m, const Candidates& c, const double* xt) {
    thread_local std::vector<int> listed;
    const int n = list_pairs(m, c, xt, listed);
    offsets_[t + 1] = n;
    code_offsets_[t + 1] = code_pairs(c, listed, n, nullptr);
  });
  for (int t = 0; t < nt; ++t) {
    offsets_[t + 1] += offsets_[t];
    code_offsets_[t + 1] += code_offsets_[t];
  }
  codes_.resize(code_offsets_.back());
  for_each_pair_by_cell([&](int t, int m, const Candidates& c, const double* xt) {
    thread_local std::vector<int> listed;
    const int n = list_pairs(m, c, xt, listed);
    code_pairs(c, listed, n, codes_.data() + code_offsets_[t]);
  });
  code_offsets_.pop_back();
}

std::size_t NeighborList::memory_bytes() const {
  return heap_bytes(order_) + heap_bytes(sources_) + heap_bytes(target_order_) + heap_bytes(rank_) +
         heap_bytes(targets_) + heap_bytes(image_shifts_) + heap_bytes(offsets_) + heap_bytes(code_offsets_) +
         heap_bytes(codes_);
}

}  // namespace rbcflow
