#include "ewald_parameters.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "bspline.h"

namespace rbcflow {
namespace {

constexpr double pi = std::numbers::pi;
constexpr int kMaxGridSide = 2048;
// Memory limits: grids of at most 2^26 points (up to 72 bytes each in work arrays, 4.5 GB) and
// at most 1e9 real-space pairs (6 bytes each in the neighbour list, 6 GB).
constexpr double kMaxGridPoints = 67108864.0;
constexpr double kMaxPairs = 1e9;

// Costs of one product measured on the 2-core development machine, 1 thread, on the points
// the solver sums over: the nodes of tube27's 27 red cells, stored cell by cell
// (`bench_spme --benchmark_filter=Tube27Cells`, medians of 3): seconds per real-space pair (as
// counted here, at uniform density; the stresslet's is the first product's, which computes
// the coefficients its plan keeps), per grid node and density component of spreading or
// interpolation, per component of a transform of K points per K log2 K (FFTW_ESTIMATE plans),
// per complex mode of the influence function. Clustered and ordered points cost a quarter of
// random ones in the unit cube (`--benchmark_filter=Layer/100000/1`: 20-23 ns a pair, 0.45-0.5
// ns a node), and the transforms the same, so the former constants, measured on random points,
// chose too fine grids for cells (tube27: 84 x 84 x 168 for both layers).
struct CostModel {
  double pair, node, fft, mode;
};
constexpr CostModel kCostStokeslet{8e-9, 0.3e-9, 0.35e-9, 2.5e-9};
constexpr CostModel kCostStresslet{40e-9, 0.35e-9, 0.37e-9, 15e-9};

bool is_fft_friendly(int n) {
  for (int f : {2, 3, 5, 7})
    while (n % f == 0) n /= f;
  return n == 1;
}

// Smallest even 2^a 3^b 5^c 7^d >= n.
int fft_friendly_size(int n) {
  int m = n + (n % 2);
  while (!is_fft_friendly(m)) m += 2;
  return m;
}

// Cutoff at which the real-space estimate equals `target` (bisection in log r_c: the estimate
// decreases for xi r_c > 1).
double cutoff_for(EwaldKernel kernel, const PeriodicBox& box, double xi, double target) {
  double lo = 1.0 / xi, hi = 40.0 / xi;
  for (int it = 0; it < 60; ++it) {
    const double mid = std::sqrt(lo * hi);
    (real_space_error(kernel, box, xi, mid) > target ? lo : hi) = mid;
  }
  return hi;
}

std::array<int, 3> grid_for(const PeriodicBox& box, double h, int order) {
  std::array<int, 3> grid{};
  for (int d = 0; d < 3; ++d)
    grid[d] = fft_friendly_size(
        std::max(2 * order, static_cast<int>(std::ceil(box.length(d) / h - 1e-9))));
  return grid;
}

// Largest spacing h (bisection in log h) whose grid error stays below `target`; 0 if none
// does within kMaxGridSide points per side.
double spacing_for(EwaldKernel kernel, const PeriodicBox& box, double xi, int order,
                   double target) {
  const Eigen::Vector3d& L = box.lengths();
  double lo = L.maxCoeff() / kMaxGridSide, hi = L.minCoeff() / (2 * order);
  const auto error = [&](double h) { return spme_grid_error(kernel, box, xi, h, order); };
  if (error(hi) <= target) return hi;
  if (error(lo) > target) return 0.0;
  for (int it = 0; it < 16; ++it) {
    const double mid = std::sqrt(lo * hi);
    (error(mid) > target ? hi : lo) = mid;
  }
  return lo;
}

double modelled_seconds(EwaldKernel kernel, const EwaldParameters& p, double n_sources,
                        double n_targets, double neighbours, double real_space_weight) {
  const CostModel& c = kernel == EwaldKernel::stokeslet ? kCostStokeslet : kCostStresslet;
  const double in = kernel == EwaldKernel::stokeslet ? 3.0 : 6.0;  // density components
  const double nodes = static_cast<double>(p.order) * p.order * p.order;
  const double points = static_cast<double>(p.grid[0]) * p.grid[1] * p.grid[2];
  return real_space_weight * c.pair * n_targets * neighbours + c.node * nodes * (in * n_sources + 3.0 * n_targets) +
         c.fft * (in + 3.0) * points * std::log2(points) + c.mode * points / 2.0;
}

}  // namespace

double EwaldParameters::alpha() const { return pi / (xi * xi); }

void validate(const EwaldParameters& p, const PeriodicBox& box) {
  if (!(std::isfinite(p.xi) && p.xi > 0.0))
    throw std::invalid_argument("Ewald parameters: xi must be positive, got " +
                                std::to_string(p.xi));
  if (!(std::isfinite(p.cutoff) && p.cutoff > 0.0))
    throw std::invalid_argument("Ewald parameters: the real-space cutoff must be positive, got " +
                                std::to_string(p.cutoff));
  if (p.cutoff > 16.0 * box.lengths().maxCoeff())
    throw std::invalid_argument("Ewald parameters: the real-space cutoff " +
                                std::to_string(p.cutoff) + " exceeds 16 box lengths; increase xi");
  check_spline_order(p.order);
  for (int d = 0; d < 3; ++d) {
    if (p.grid[d] < 2 * p.order || p.grid[d] % 2 != 0)
      throw std::invalid_argument(
          "Ewald parameters: SPME grid sides must be even and at least "
          "twice the spline order (" +
          std::to_string(2 * p.order) + "), got " + std::to_string(p.grid[d]));
  }
}

EwaldChoice choose_ewald_parameters(EwaldKernel kernel, double tolerance, const PeriodicBox& box,
                                    long n_sources, long n_targets) {
  return choose_ewald_parameters(kernel, tolerance, box, n_sources, n_targets, RealSpaceUse{});
}

EwaldChoice choose_ewald_parameters(EwaldKernel kernel, double tolerance, const PeriodicBox& box,
                                    long n_sources, long n_targets, const RealSpaceUse& real_space) {
  if (!(real_space.weight > 0.0 && real_space.weight <= 1.0))
    throw std::invalid_argument("Ewald parameters: the real-space weight must be in (0, 1], got " +
                                std::to_string(real_space.weight));
  if (!(real_space.max_pairs >= 1.0 && real_space.max_pairs <= kMaxPairs))
    throw std::invalid_argument("Ewald parameters: the real-space pair bound must be in [1, 1e9], got " +
                                std::to_string(real_space.max_pairs));
  if (!(tolerance >= 1e-10 && tolerance <= 1e-3)) {
    std::ostringstream msg;
    msg << "Ewald parameters: tolerance must be between 1e-10 and 1e-3, got " << tolerance;
    throw std::invalid_argument(msg.str());
  }
  if (n_sources < 1)
    throw std::invalid_argument("Ewald parameters: need at least one source point");
  if (n_targets < 0) n_targets = n_sources;

  const double part = 0.5 * tolerance / std::sqrt(2.0);  // real space and grid, each
  const Eigen::Vector3d& L = box.lengths();
  const double V = box.volume(), ns = static_cast<double>(n_sources);
  const double nt = static_cast<double>(n_targets);
  // xi from a cutoff of two box lengths to a grid of kMaxGridSide points per side.
  const double decay = std::sqrt(std::log(1.0 / part));
  const double xi_lo = decay / (2.0 * L.maxCoeff()), xi_hi = 0.5 * kMaxGridSide / L.minCoeff();
  constexpr int n_xi = 32;

  EwaldChoice best;
  best.kernel = kernel;
  best.tolerance = tolerance;
  best.estimated_seconds = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_xi; ++i) {
    const double xi = xi_lo * std::pow(xi_hi / xi_lo, i / (n_xi - 1.0));
    const double cutoff = cutoff_for(kernel, box, xi, part);
    const double neighbours = ns * 4.0 / 3.0 * pi * cutoff * cutoff * cutoff / V;
    if (neighbours * nt > real_space.max_pairs) continue;
    for (int order = kMinSplineOrder; order <= kMaxSplineOrder; ++order) {
      const double h = spacing_for(kernel, box, xi, order, part);
      if (h <= 0.0) continue;
      EwaldParameters p{xi, cutoff, grid_for(box, h, order), order};
      if (static_cast<double>(p.grid[0]) * p.grid[1] * p.grid[2] > kMaxGridPoints) continue;
      const double seconds = modelled_seconds(kernel, p, ns, nt, neighbours, real_space.weight);
      if (seconds < best.estimated_seconds) {
        best.parameters = p;
        best.estimated_seconds = seconds;
        best.neighbours_per_target = neighbours;
      }
    }
  }
  if (!std::isfinite(best.estimated_seconds)) {
    std::ostringstream msg;
    msg << "Ewald parameters: tolerance " << tolerance << " for " << n_sources
        << " sources needs more than " << real_space.max_pairs << " real-space pairs or " << kMaxGridPoints
        << " grid points";
    throw std::invalid_argument(msg.str());
  }
  const EwaldParameters& p = best.parameters;
  best.real_space_error = real_space_error(kernel, box, p.xi, p.cutoff);
  best.grid_error = spme_grid_error(kernel, box, p.xi, p.grid, p.order);
  return best;
}

std::ostream& operator<<(std::ostream& os, const EwaldParameters& p) {
  return os << "xi = " << p.xi << " (alpha = pi/xi^2 = " << p.alpha() << "), real-space cutoff "
            << p.cutoff << ", SPME grid " << p.grid[0] << " x " << p.grid[1] << " x " << p.grid[2]
            << ", B-spline order " << p.order;
}

std::ostream& operator<<(std::ostream& os, const EwaldChoice& c) {
  const EwaldParameters& p = c.parameters;
  os << "Ewald sum, " << to_string(c.kernel) << ", tolerance " << c.tolerance << ":\n"
     << "  xi = " << p.xi << " (alpha = pi/xi^2 = " << p.alpha() << ")\n"
     << "  real-space cutoff " << p.cutoff << " (" << c.neighbours_per_target
     << " neighbours per target)\n"
     << "  SPME grid " << p.grid[0] << " x " << p.grid[1] << " x " << p.grid[2]
     << ", B-spline order " << p.order << "\n"
     << "  estimated error: real space " << c.real_space_error << ", grid " << c.grid_error
     << "; estimated time per product " << 1e3 * c.estimated_seconds << " ms (1 thread)";
  return os;
}

std::string to_string(const EwaldChoice& c) {
  std::ostringstream s;
  s << c;
  return s.str();
}

}  // namespace rbcflow
