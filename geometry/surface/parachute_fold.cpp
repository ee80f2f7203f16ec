#include "geometry/surface/parachute_fold.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/format_number.h"

namespace rbcflow {
namespace {

constexpr double pi = std::numbers::pi;
// The parachute's shape, in units of its outer radius R: trailing rim half-thickness w, nose
// semi-axis c along z, the least thickness left at the dimple's centre; points per piece of the
// meridian polyline (its volume and area converge as the square of the spacing: 1e-5 here).
constexpr double kRim = 0.12, kNose = 0.8, kThinnest = 0.15;
constexpr int kPoints = 400;

// The meridian (rho, z) from the nose (0, length) down the side, round the rim (bottom at z = 0)
// and up the dimple to (0, dimple).
struct Meridian {
  std::vector<double> rho, z;

  Meridian(double R, double length, double dimple) {
    const double w = kRim * R, c = kNose * R;
    auto add = [&](double r, double h) { rho.push_back(r), z.push_back(h); };
    for (int i = 0; i < kPoints; ++i) {  // nose: quarter ellipse
      const double t = 0.5 * pi * i / kPoints;
      add(R * std::sin(t), length - c + c * std::cos(t));
    }
    for (int i = 0; i < kPoints; ++i) add(R, length - c - (length - c - w) * i / kPoints);  // side
    for (int i = 0; i < kPoints; ++i) {  // rim: half circle
      const double t = -pi * i / kPoints;
      add(R - w + w * std::cos(t), w + w * std::sin(t));
    }
    for (int i = 0; i <= kPoints; ++i) {  // dimple: quarter ellipse to the axis
      const double t = 0.5 * pi * i / kPoints;
      add((R - 2 * w) * std::cos(t), w + (dimple - w) * std::sin(t));
    }
  }
  // Cumulative area of revolution from the nose (frusta).
  std::vector<double> cumulative_area() const {
    std::vector<double> a(rho.size(), 0.0);
    for (std::size_t i = 1; i < rho.size(); ++i)
      a[i] = a[i - 1] + pi * (rho[i - 1] + rho[i]) * std::hypot(rho[i] - rho[i - 1], z[i] - z[i - 1]);
    return a;
  }
  double area() const { return cumulative_area().back(); }
  double volume() const {  // pi int rho^2 dz round the closed meridian (the axis adds nothing)
    double v = 0;
    for (std::size_t i = 1; i < rho.size(); ++i)
      v += pi / 3 * (rho[i - 1] * rho[i - 1] + rho[i - 1] * rho[i] + rho[i] * rho[i]) * (z[i - 1] - z[i]);
    return v;
  }
};

// Smallest x in [lo, hi] with f(x) >= target, f increasing (bisection to round-off).
template <class F>
double bisect(F f, double lo, double hi, double target) {
  for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

ParachuteFold fold_into_parachute(const SHSurface& cell, double radius) {
  if (!(radius > 0)) throw std::invalid_argument("fold_into_parachute: the radius must be positive");
  const int order = cell.order();
  const SHTransform fine = SHTransform::gauss(2 * order);
  const SurfaceGeometry g = cell.geometry(fine);
  const double volume = enclosed_volume(g), area = surface_area(g);

  // The parachute of the cell's volume and area: for a length, the dimple depth that leaves the
  // volume (the volume falls as the dimple deepens); then the length that gives the area.
  const double R = radius, w = kRim * R;
  auto dimple_for = [&](double length) {
    return bisect([&](double d) { return -Meridian(R, length, d).volume(); }, w, length - kThinnest * R, -volume);
  };
  const double shortest = bisect([&](double L) { return Meridian(R, L, w).volume(); }, kNose * R + w, 100.0, volume);
  if (!(Meridian(R, shortest, w).area() < area)) {
    // The least area that holds the volume within radius R falls with R up to about the
    // radius of the cylinder as long as it is wide, cbrt(V / pi), and rises beyond.
    const bool narrow = R < std::cbrt(volume / pi);
    throw std::runtime_error("fold_into_parachute: a parachute of radius " + format_number(R) +
                             " holding the cell's volume has more than its area " + format_number(area) +
                             (narrow ? ": the radius is too small for the cell" : ": the radius is too large for a folded cell"));
  }
  const double length = bisect([&](double L) { return Meridian(R, L, dimple_for(L)).area(); }, shortest,
                               100.0, area);
  const Meridian target(R, length, dimple_for(length));
  const std::vector<double> along = target.cumulative_area();

  // Equal area: each point's share of the disc's surface counted from the top face's centre.
  const Eigen::MatrixXd& x = g.x;
  const Eigen::VectorXd r = x.leftCols<2>().rowwise().norm();
  const double r_max = r.maxCoeff();
  std::vector<int> by_key(x.rows());
  std::iota(by_key.begin(), by_key.end(), 0);
  auto key = [&](int p) { return x(p, 2) >= 0 ? r[p] : 2 * r_max - r[p]; };
  std::sort(by_key.begin(), by_key.end(), [&](int a, int b) { return key(a) < key(b); });
  Eigen::MatrixXd y(x.rows(), 3);
  double before = 0;
  for (std::size_t i = 0; i < by_key.size();) {
    std::size_t j = i;  // a ring: points with the same key share the area before them
    double ring = 0;
    for (; j < by_key.size() && key(by_key[j]) - key(by_key[i]) < 1e-12; ++j) ring += g.area_weight[by_key[j]];
    const double share = (before + 0.5 * ring) / area * along.back();
    const std::size_t k = std::clamp<std::size_t>(
        std::lower_bound(along.begin(), along.end(), share) - along.begin(), 1, along.size() - 1);
    const double s = (share - along[k - 1]) / (along[k] - along[k - 1]);
    const double rho = target.rho[k - 1] + s * (target.rho[k] - target.rho[k - 1]);
    const double z = target.z[k - 1] + s * (target.z[k] - target.z[k - 1]);
    for (std::size_t q = i; q < j; ++q) {
      const int p = by_key[q];
      const double phi = std::atan2(x(p, 1), x(p, 0));
      y.row(p) << rho * std::cos(phi), rho * std::sin(phi), z;
    }
    before += ring;
    i = j;
  }
  ParachuteFold out;
  out.surface = SHSurface(fine.analyze(y, order));
  // The projection onto the cell's order moves the volume by a little: a stretch along z
  // (the volume is linear in it) restores it exactly, and the centroid goes back to the origin.
  const SurfaceGeometry folded = out.surface.geometry(fine);
  Eigen::Matrix3d stretch = Eigen::Matrix3d::Identity();
  stretch(2, 2) = volume / enclosed_volume(folded);
  out.surface.transform(stretch, volume_centroid(folded));
  out.surface.translate(-volume_centroid(out.surface.geometry(fine)));
  const Eigen::MatrixXd final_x = out.surface.geometry(fine).x;
  out.radius = final_x.leftCols<2>().rowwise().norm().maxCoeff();
  out.length = final_x.col(2).maxCoeff() - final_x.col(2).minCoeff();
  out.dimple = target.z.back() - 0.0;
  return out;
}

}  // namespace rbcflow
