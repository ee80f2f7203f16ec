#include "cell_placement.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "cell_overlap.h"
#include "wall_distance.h"

namespace rbcflow {
namespace {

// Random sequential addition: trial positions per cell before it counts as jammed.
constexpr int kTrialsPerCell = 4000;
// Compression: starting scale (halved until every cell fits); growth factor per successful
// growth (halved on failure, times 1.5 on success, within these bounds); the compression gives
// up after kPatience sweeps without growth or kMaxSweeps in all. Random moves: the step
// (a fraction of the scaled cell radius) is halved or doubled to keep about a third accepted.
constexpr double kStartScale = 0.5;
constexpr int kMaxSweeps = 4000, kPatience = 150;
constexpr double kMaxGrowth = 0.05, kMinGrowth = 1e-4;
constexpr double kMaxStep = 0.15, kMinStep = 1e-3;  // translation / scaled radius; rotation, rad

// Uniform double in [0, 1) from the top 53 bits: the same sequence with every standard library.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

Eigen::Vector3d random_direction(std::mt19937_64& rng) {
  const double z = 2.0 * uniform(rng) - 1.0, phi = 2.0 * std::numbers::pi * uniform(rng);
  const double r = std::sqrt(1.0 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// A uniformly random rotation: the reference's z axis to a uniform direction (or to `axis`),
// after a uniform spin about z.
Eigen::Matrix3d random_rotation(std::mt19937_64& rng, const Eigen::Vector3d* axis) {
  const Eigen::Vector3d u = axis ? *axis : random_direction(rng);
  const double spin = 2.0 * std::numbers::pi * uniform(rng);
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), u).toRotationMatrix() *
         Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

struct Problem {
  const PlacementSpec& spec;
  const CellOverlap& overlap;
  const Eigen::Vector3d* axis;  // the vessel axis for along_axis orientations, else null

  bool fits(const CellPose& p, const std::vector<CellPose>& cells, int skip = -1) const {
    if (!overlap.inside_wall(p) || !overlap.apart(p, p, true)) return false;
    for (int i = 0; i < static_cast<int>(cells.size()); ++i)
      if (i != skip && !overlap.apart(cells[i], p)) return false;
    return true;
  }

  CellPose random_pose(std::mt19937_64& rng, double scale) const {
    CellPose p;
    for (int k = 0; k < 3; ++k) p.position[k] = spec.box[k] * uniform(rng);
    p.rotation = random_rotation(rng, axis);
    p.scale = scale;
    return p;
  }

  // Random sequential addition of up to spec.count cells at `scale`.
  std::vector<CellPose> add_sequentially(std::mt19937_64& rng, double scale) const {
    std::vector<CellPose> cells;
    for (int k = 0; k < spec.count; ++k) {
      bool placed = false;
      for (int trial = 0; trial < kTrialsPerCell && !placed; ++trial) {
        const CellPose p = random_pose(rng, scale);
        if ((placed = fits(p, cells))) cells.push_back(p);
      }
      if (!placed) break;
    }
    return cells;
  }

  // One Monte Carlo sweep: each cell tries a random small move (a turn about its own axis
  // only, for along_axis orientations); a move is kept when it overlaps nothing. Returns the
  // fraction kept.
  double sweep(std::mt19937_64& rng, std::vector<CellPose>& cells, double step) const {
    int kept = 0;
    for (int i = 0; i < static_cast<int>(cells.size()); ++i) {
      CellPose p = cells[i];
      for (int k = 0; k < 3; ++k) p.position[k] += step * overlap.radius() * p.scale * (2.0 * uniform(rng) - 1.0);
      const Eigen::Vector3d turn_axis = axis ? Eigen::Vector3d(p.rotation.col(2)) : random_direction(rng);
      p.rotation = Eigen::AngleAxisd(step * (2.0 * uniform(rng) - 1.0), turn_axis).toRotationMatrix() * p.rotation;
      if (fits(p, cells, i)) {
        cells[i] = p;
        ++kept;
      }
    }
    return static_cast<double>(kept) / static_cast<double>(cells.size());
  }

  bool all_fit(const std::vector<CellPose>& cells) const {
    for (int i = 0; i < static_cast<int>(cells.size()); ++i)
      if (!fits(cells[i], cells, i)) return false;
    return true;
  }
};

void validate(const PlacementSpec& s) {
  if (!(s.box.minCoeff() > 0)) throw std::invalid_argument("cell placement: the box sides must be positive");
  if (s.count < 0) throw std::invalid_argument("cell placement: the cell count must not be negative");
  if (!(s.gap >= 0)) throw std::invalid_argument("cell placement: the gap must not be negative");
  if (s.check_order < 4) throw std::invalid_argument("cell placement: the check order must be at least 4");
}

std::string percent(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace

Placement place_cells(const SHSurface& reference, const PlacementSpec& spec, const VesselMesh* vessel) {
  validate(spec);
  const std::unique_ptr<WallDistance> wall = vessel ? std::make_unique<WallDistance>(*vessel) : nullptr;
  const CellOverlap overlap(reference, spec.check_order, spec.box, wall.get(), spec.gap);
  const double cell_volume = enclosed_volume(reference.geometry(SHTransform::gauss(reference.order())));
  const double space = vessel ? lumen_volume(*vessel) : spec.box.prod();
  auto hematocrit = [&](double cells, double scale) { return cells * cell_volume * std::pow(scale, 3) / space; };

  // The vessel axis: the one periodic axis of the wall; narrow tubes from the lumen volume
  // per length, D = 2 sqrt(V / (pi L)), against the cell diameter 2 r.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  bool narrow = false;
  if (vessel && (vessel->period.array() > 0).count() == 1) {
    int a = 0;
    vessel->period.maxCoeff(&a);
    axis = Eigen::Vector3d::Unit(a);
    narrow = std::sqrt(space / (std::numbers::pi * vessel->period[a])) < kNarrowTubeRatio * overlap.radius();
  }
  const bool along = spec.orientation == CellOrientation::along_axis ||
                     (spec.orientation == CellOrientation::automatic && narrow);
  const Problem problem{spec, overlap, along ? &axis : nullptr};

  auto finish = [&](const std::vector<CellPose>& cells, int sweeps) {
    Placement out;
    for (const CellPose& c : cells) out.cells.push_back({c.position, c.rotation});
    out.hematocrit = hematocrit(static_cast<double>(cells.size()), 1.0);
    out.compression_sweeps = sweeps;
    return out;
  };

  std::mt19937_64 rng(spec.seed);
  const std::vector<CellPose> sequential = problem.add_sequentially(rng, 1.0);
  if (static_cast<int>(sequential.size()) == spec.count) return finish(sequential, 0);

  // Shrink, then grow: place all cells small, then move and grow them until full size.
  double scale = kStartScale;
  std::vector<CellPose> cells = problem.add_sequentially(rng, scale);
  while (static_cast<int>(cells.size()) < spec.count && scale > 0.1) {
    scale *= 0.5;
    cells = problem.add_sequentially(rng, scale);
  }
  int sweeps = 0;
  if (static_cast<int>(cells.size()) == spec.count && hematocrit(spec.count, 1.0) < 1.0 && !sequential.empty()) {
    double growth = kMaxGrowth, step = kMaxStep;
    for (int idle = 0; sweeps < kMaxSweeps && scale < 1.0 && idle < kPatience; ++sweeps) {
      const double accepted = problem.sweep(rng, cells, step);
      step = std::clamp(accepted < 0.3 ? 0.5 * step : accepted > 0.5 ? 2.0 * step : step, kMinStep, kMaxStep);
      std::vector<CellPose> grown = cells;
      const double next = std::min(1.0, scale * (1.0 + growth));
      for (CellPose& c : grown) c.scale = next;
      if (problem.all_fit(grown)) {
        cells = std::move(grown);
        scale = next;
        growth = std::min(kMaxGrowth, 1.5 * growth);
        idle = 0;
      } else {
        growth = std::max(kMinGrowth, 0.5 * growth);
        ++idle;
      }
    }
    if (scale >= 1.0) return finish(cells, sweeps);
  }
  std::string message = "cell placement: only " + std::to_string(sequential.size()) + " of " +
                        std::to_string(spec.count) + " cells fit (hematocrit " +
                        percent(hematocrit(static_cast<double>(sequential.size()), 1.0)) + " of the " +
                        percent(hematocrit(spec.count, 1.0)) + " requested) by random sequential addition";
  if (sequential.empty())
    message.append("; not even one cell fits (the cell's largest diameter is " + percent(2.0 * overlap.radius()) + ")");
  else if (hematocrit(spec.count, 1.0) >= 1.0)
    message.append("; the cells' volume exceeds the space");
  else
    message.append(static_cast<int>(cells.size()) == spec.count
                     ? "; compressing all of them from a smaller size stopped at " + percent(100.0 * scale) +
                           "% of full size after " + std::to_string(sweeps) + " sweeps"
                     : "; they do not fit even at " + percent(100.0 * scale) + "% of full size");
  message.append(" (gap " + percent(spec.gap) + "): lower the count or hematocrit, or enlarge the box");
  throw std::runtime_error(message);
}

std::vector<SHSurface> placed_surfaces(const SHSurface& reference, const std::vector<PlacedCell>& cells) {
  const Eigen::Vector3d centroid = volume_centroid(reference.geometry(SHTransform::gauss(2 * reference.order())));
  std::vector<SHSurface> out;
  for (const PlacedCell& c : cells) {
    SHSurface s = reference;
    s.rotate(c.rotation, centroid);
    s.translate(c.position - centroid);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace rbcflow
