#include "geometry/contact/cell_placement.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "geometry/contact/cell_overlap.h"
#include "geometry/surface/parachute_fold.h"
#include "geometry/contact/wall_distance.h"
#include "geometry/format_number.h"

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
// After a growth, the cells it made touch are moved apart: trials per cell and pass, passes,
// and the step of those moves (as kMaxStep).
constexpr int kRepairTrials = 40, kRepairRounds = 6;
constexpr double kRepairStep = 0.3;
// Pre-deformed cells in narrow tubes: the stretched cell keeps this fraction of the lumen
// radius free (beside the gap) against the facets of the meshed wall; the squeeze across the
// tube is searched in steps of kSqueezeStep down to kSmallestSqueeze, the stretch along it up
// to kLongestStretch (beyond, the start is too far from any shape the cell takes in a tube).
constexpr double kStackMargin = 0.05, kSqueezeStep = 0.005, kSmallestSqueeze = 0.3, kLongestStretch = 2.5;

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

// The placed cells by the bin of their centre: a periodic grid of bins at least `reach` wide
// (two full-size cell radii and the gap), so that every cell a cell can touch has its centre in
// the 27 bins around the cell's own (every bin of a direction with fewer than 3). An overlap test
// then visits the cells near it instead of all of them: O(1) per test instead of O(count).
class Packing {
 public:
  Packing(const Eigen::Vector3d& box, double reach) {
    for (int d = 0; d < 3; ++d) {
      n_[d] = std::max(1, static_cast<int>(std::floor(box[d] / reach)));
      side_[d] = box[d] / n_[d];
    }
    bins_.resize(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2]);
  }
  const std::vector<CellPose>& cells() const { return cells_; }
  int size() const { return static_cast<int>(cells_.size()); }
  void add(const CellPose& p) {
    bins_[bin(p.position)].push_back(size());
    cells_.push_back(p);
  }
  void set_scale(double scale) {
    for (CellPose& c : cells_) c.scale = scale;
  }
  void replace(int i, const CellPose& p) {
    std::vector<int>& from = bins_[bin(cells_[i].position)];
    from.erase(std::find(from.begin(), from.end(), i));
    bins_[bin(p.position)].push_back(i);
    cells_[i] = p;
  }
  // Whether f(i) holds for every cell i whose centre is in the bins around x.
  template <class F>
  bool all_near(const Eigen::Vector3d& x, F&& f) const {
    std::array<std::vector<int>, 3> around;
    for (int d = 0; d < 3; ++d) {
      const int b = index(x[d], d);
      for (int o = -1; o <= 1; ++o) {
        const int k = ((b + o) % n_[d] + n_[d]) % n_[d];
        if (std::find(around[d].begin(), around[d].end(), k) == around[d].end()) around[d].push_back(k);
      }
    }
    for (const int i : around[0])
      for (const int j : around[1])
        for (const int k : around[2])
          for (const int c : bins_[(static_cast<std::size_t>(i) * n_[1] + j) * n_[2] + k])
            if (!f(c)) return false;
    return true;
  }

 private:
  int index(double x, int d) const {
    const int k = static_cast<int>(std::floor(x / side_[d])) % n_[d];
    return k < 0 ? k + n_[d] : k;
  }
  std::size_t bin(const Eigen::Vector3d& x) const {
    return (static_cast<std::size_t>(index(x[0], 0)) * n_[1] + index(x[1], 1)) * n_[2] + index(x[2], 2);
  }
  std::array<int, 3> n_{};
  Eigen::Vector3d side_;
  std::vector<std::vector<int>> bins_;
  std::vector<CellPose> cells_;
};

struct Problem {
  const PlacementSpec& spec;
  const CellOverlap& overlap;
  const Eigen::Vector3d* axis;  // the vessel axis for along_axis orientations, else null

  Packing empty() const { return Packing(spec.box, 2.0 * overlap.radius() + spec.gap); }

  // Against the wall and its own periodic images a cell is tested at full size even while the
  // compression holds the cells smaller: those constraints do not move, so a cell must never sit
  // where it could not grow (a daughter narrower than the cell would hold it small for good).
  // The tests run cheapest first: the wall's (a closest-point query per vertex near it) last.
  bool fits(const CellPose& p, const Packing& packing, int skip = -1) const {
    if (!apart_from_others(p, packing, skip)) return false;
    CellPose full = p;
    full.scale = 1.0;
    return overlap.apart(full, full, true) && overlap.inside_wall(full);
  }
  bool apart_from_others(const CellPose& p, const Packing& packing, int skip) const {
    return packing.all_near(p.position,
                            [&](int i) { return i == skip || overlap.apart(packing.cells()[i], p); });
  }

  CellPose random_pose(std::mt19937_64& rng, double scale) const {
    CellPose p;
    for (int k = 0; k < 3; ++k) p.position[k] = spec.box[k] * uniform(rng);
    p.rotation = random_rotation(rng, axis);
    p.scale = scale;
    return p;
  }

  // Random sequential addition of up to spec.count cells at `scale`.
  Packing add_sequentially(std::mt19937_64& rng, double scale) const {
    Packing cells = empty();
    for (int k = 0; k < spec.count; ++k) {
      bool placed = false;
      for (int trial = 0; trial < kTrialsPerCell && !placed; ++trial) {
        const CellPose p = random_pose(rng, scale);
        if ((placed = fits(p, cells))) cells.add(p);
      }
      if (!placed) break;
    }
    return cells;
  }

  // One Monte Carlo sweep: each cell tries a random small move; a move is kept when it
  // overlaps nothing. Returns the fraction kept.
  double sweep(std::mt19937_64& rng, Packing& cells, double step) const {
    int kept = 0;
    for (int i = 0; i < cells.size(); ++i) {
      const CellPose p = moved(rng, cells.cells()[i], step);
      if (fits(p, cells, i)) {
        cells.replace(i, p);
        ++kept;
      }
    }
    return static_cast<double>(kept) / static_cast<double>(cells.size());
  }

  // After a growth: the cells have not moved, so only the cell-cell tests can fail (the wall
  // and the periodic images were tested at full size). The cells that touch another.
  std::vector<int> touching(const Packing& cells) const {
    std::vector<int> out;
    for (int i = 0; i < cells.size(); ++i)
      if (!apart_from_others(cells.cells()[i], cells, i)) out.push_back(i);
    return out;
  }

  // Moves the touching cells of a grown packing apart, each by random moves (a step of up to
  // kRepairStep of its scaled radius and angle) that must clear everything, in up to
  // kRepairRounds passes over those still touching. A growth then costs work in proportion to
  // the few cells it makes touch, not a sweep of all cells per failed try: the compression's
  // sweeps no longer grow with the count. Returns whether no cell touches another.
  bool separate(std::mt19937_64& rng, Packing& cells, std::vector<int> touching_cells) const {
    for (int round = 0; round < kRepairRounds && !touching_cells.empty(); ++round) {
      for (const int i : touching_cells) {
        if (apart_from_others(cells.cells()[i], cells, i)) continue;  // its partner moved away
        for (int trial = 0; trial < kRepairTrials; ++trial) {
          const CellPose p = moved(rng, cells.cells()[i], kRepairStep);
          if (fits(p, cells, i)) {
            cells.replace(i, p);
            break;
          }
        }
      }
      std::erase_if(touching_cells, [&](int i) { return apart_from_others(cells.cells()[i], cells, i); });
    }
    return touching_cells.empty();
  }

  // A random small move of a cell (a turn about its own axis only, for along_axis orientations).
  CellPose moved(std::mt19937_64& rng, CellPose p, double step) const {
    for (int k = 0; k < 3; ++k) p.position[k] += step * overlap.radius() * p.scale * (2.0 * uniform(rng) - 1.0);
    const Eigen::Vector3d turn_axis = axis ? Eigen::Vector3d(p.rotation.col(2)) : random_direction(rng);
    p.rotation = Eigen::AngleAxisd(step * (2.0 * uniform(rng) - 1.0), turn_axis).toRotationMatrix() * p.rotation;
    return p;
  }
};

void validate(const PlacementSpec& s) {
  if (!(s.box.minCoeff() > 0)) throw std::invalid_argument("cell placement: the box sides must be positive");
  if (s.count < 0) throw std::invalid_argument("cell placement: the cell count must not be negative");
  if (!(s.gap >= 0)) throw std::invalid_argument("cell placement: the gap must not be negative");
  if (s.check_order < 4) throw std::invalid_argument("cell placement: the check order must be at least 4");
}

std::string percent(double x) { return format_number(x, 3); }

// The narrowest tubes. Their geometry: the spacing of `count` cells along axis `a`, the lumen's
// equivalent radius, the radius a deformed cell may fill (the margin and the gap kept free
// against the facets of the meshed wall).
struct NarrowTube {
  int axis;
  double length, spacing, lumen_radius, fit_radius;

  NarrowTube(const PlacementSpec& spec, int a, double lumen)
      : axis(a), length(spec.box[a]), spacing(length / spec.count),
        lumen_radius(std::sqrt(lumen / (std::numbers::pi * length))),
        fit_radius((1.0 - kStackMargin) * lumen_radius - spec.gap) {}
};

// `count` cells of the shape `overlap` at equal spacing along the axis through the lumen's
// centre (one random offset for the stack, a random turn about the axis for each cell, given to
// `rotation`); `what` names the shape in the error when they do not fit.
std::vector<PlacedCell> stack_on_axis(const CellOverlap& overlap, const PlacementSpec& spec, const VesselMesh& vessel,
                                      const NarrowTube& tube, std::mt19937_64& rng,
                                      const std::function<Eigen::Matrix3d(const Eigen::Vector3d&)>& rotation,
                                      const std::string& what) {
  const Problem problem{spec, overlap, nullptr};
  const int a = tube.axis;
  // The lumen's centre in the cross-section: the mean of the wall's nodes.
  Eigen::Vector3d centre = vessel.surface.points.colwise().mean().transpose();
  const Eigen::Vector3d u = Eigen::Vector3d::Unit((a + 1) % 3), v = Eigen::Vector3d::Unit((a + 2) % 3);
  centre[a] = tube.spacing * uniform(rng);
  Packing poses = problem.empty();
  std::vector<PlacedCell> out;
  for (int k = 0; k < spec.count; ++k) {
    const double turn = 2.0 * std::numbers::pi * uniform(rng);
    CellPose pose;
    pose.rotation = rotation(std::cos(turn) * u + std::sin(turn) * v);
    pose.position = centre + k * tube.spacing * Eigen::Vector3d::Unit(a);
    pose.position[a] = std::fmod(pose.position[a], tube.length);
    if (!problem.fits(pose, poses)) {
      throw std::runtime_error("cell placement: " + std::to_string(spec.count) + " cells " + what +
                               " do not fit at spacing " + percent(tube.spacing) + " (gap " + percent(spec.gap) +
                               "): lower the count or hematocrit");
    }
    poses.add(pose);
    out.push_back({pose.position, pose.rotation});
  }
  return out;
}

// Edge-on: each cell stretched in its own frame by diag(s_axis, s_width, s_thickness), product
// 1: the plane of the cell (the reference's x-y) contains the tube axis (along the reference's
// x). s_width is the largest factor that fits the cell in the lumen with s_axis = 1 / s_width,
// which keeps the faces' area (the red cell's membrane is stiff in dilatation) and the
// thickness; where the spacing does not allow that stretch, s_axis is what it allows and the
// thickness grows to keep the volume.
Placement stack_stretched(const SHSurface& reference, const PlacementSpec& spec, const VesselMesh& vessel,
                          const WallDistance& wall, const NarrowTube& tube, std::mt19937_64& rng) {
  const CellOverlap undeformed(reference, spec.check_order, spec.box, &wall, spec.gap);
  const Eigen::MatrixX3d& p = undeformed.mesh().points;  // reference frame, centroid at 0
  const double longest =
      std::min(kLongestStretch, (tube.spacing - 3.0 * spec.gap) / (2.0 * p.col(0).cwiseAbs().maxCoeff()));
  auto widest = [&](double s_axis, double s_width) {
    const double s_thickness = 1.0 / (s_axis * s_width);
    return ((s_width * p.col(1)).array().square() + (s_thickness * p.col(2)).array().square()).sqrt().maxCoeff();
  };
  double s_axis = 0.0, s_width = 0.0;
  for (double w = 1.0; w >= kSmallestSqueeze && s_width == 0.0 && longest > 0; w -= kSqueezeStep) {
    const double along = std::min(longest, 1.0 / w);
    if (widest(along, w) <= tube.fit_radius) s_axis = along, s_width = w;
  }
  if (s_width == 0.0) {
    throw std::runtime_error("cell placement: the tube (equivalent diameter " + percent(2.0 * tube.lumen_radius) +
                             ") is too narrow for " + std::to_string(spec.count) +
                             (spec.count == 1 ? " cell" : " cells") + " even squeezed to " +
                             percent(100.0 * kSmallestSqueeze) + "% of the width and stretched up to " +
                             percent(kLongestStretch) + "x along it within the spacing " + percent(tube.spacing) +
                             " (gap " + percent(spec.gap) + "): lower the count or hematocrit, or widen the tube");
  }
  const Eigen::Vector3d factors(s_axis, s_width, 1.0 / (s_axis * s_width));
  SHSurface stretched = reference;
  stretched.transform(factors.asDiagonal().toDenseMatrix(), undeformed.centroid());
  const CellOverlap overlap(stretched, spec.check_order, spec.box, &wall, spec.gap);
  const Eigen::Vector3d t = Eigen::Vector3d::Unit(tube.axis);
  Placement out;
  out.cells = stack_on_axis(overlap, spec, vessel, tube, rng,
                            [&](const Eigen::Vector3d& across) {  // reference x, y, z: the axis, the width, the thickness
                              Eigen::Matrix3d r;
                              r << t, across.cross(t), across;
                              return r;
                            },
                            "pre-deformed for the narrow tube (stretch " + percent(factors[0]) + ", " +
                                percent(factors[1]) + ", " + percent(factors[2]) + ")");
  for (PlacedCell& c : out.cells) c.stretch = c.rotation * factors.asDiagonal().toDenseMatrix() * c.rotation.transpose();
  out.stretch_factors = factors;
  return out;
}

// Face-on: each cell folded into a parachute (geometry/surface/parachute_fold.h) whose outer radius is
// the fit radius, the nose along the flow; the rest shape is the disc turned the same way.
Placement stack_parachutes(const SHSurface& reference, const PlacementSpec& spec, const VesselMesh& vessel,
                           const WallDistance& wall, const NarrowTube& tube, std::mt19937_64& rng) {
  SHSurface disc = reference;  // centroid at the origin
  disc.translate(-volume_centroid(reference.geometry(SHTransform::gauss(2 * reference.order()))));
  // The projection onto the cell's order overshoots the fold's radius by about 1%: two
  // corrections of the radius asked bring the result within the fit radius.
  double radius = tube.fit_radius;
  ParachuteFold fold = fold_into_parachute(disc, radius);
  for (int it = 0; it < 2 && fold.radius > tube.fit_radius; ++it)
    fold = fold_into_parachute(disc, radius *= tube.fit_radius / fold.radius);
  const std::string what = "folded into parachutes (radius " + percent(fold.radius) + ", length " +
                           percent(fold.length) + ")";
  if (fold.length + 3.0 * spec.gap > tube.spacing) {
    throw std::runtime_error("cell placement: " + std::to_string(spec.count) + " cells " + what +
                             " are longer than the spacing " + percent(tube.spacing) + " less 3 gaps (" +
                             percent(spec.gap) + "): lower the count or hematocrit, or widen the tube");
  }
  const CellOverlap overlap(fold.surface, spec.check_order, spec.box, &wall, spec.gap);
  const Eigen::Vector3d t = Eigen::Vector3d::Unit(tube.axis);
  const Eigen::Vector3d nose = spec.flow.dot(t) < 0 ? Eigen::Vector3d(-t) : t;
  Placement out;
  out.cells = stack_on_axis(overlap, spec, vessel, tube, rng,
                            [&](const Eigen::Vector3d& across) {  // reference x, y, z: across, the rest, the nose
                              Eigen::Matrix3d r;
                              r << across, nose.cross(across), nose;
                              return r;
                            },
                            what);
  out.parachute = std::move(fold.surface);
  out.parachute_radius = fold.radius;
  out.parachute_length = fold.length;
  return out;
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
  int tube_axis = -1;
  if (vessel && (vessel->period.array() > 0).count() == 1) {
    vessel->period.maxCoeff(&tube_axis);
    axis = Eigen::Vector3d::Unit(tube_axis);
    narrow = std::sqrt(space / (std::numbers::pi * vessel->period[tube_axis])) < kNarrowTubeRatio * overlap.radius();
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
  const Packing sequential = problem.add_sequentially(rng, 1.0);
  if (sequential.size() == spec.count) return finish(sequential.cells(), 0);
  if (sequential.size() == 0 && tube_axis >= 0) {
    const NarrowTube tube(spec, tube_axis, space);
    Placement out;
    if (spec.narrow_start == NarrowStart::parachute) {
      try {
        out = stack_parachutes(reference, spec, *vessel, *wall, tube, rng);
      } catch (const std::runtime_error& folded) {  // too wide to fold, or too long: try edge-on
        try {
          out = stack_stretched(reference, spec, *vessel, *wall, tube, rng);
        } catch (const std::runtime_error& stretched) {
          throw std::runtime_error(std::string(stretched.what()) + "; face-on: " + folded.what());
        }
      }
    } else {
      out = stack_stretched(reference, spec, *vessel, *wall, tube, rng);
    }
    out.hematocrit = hematocrit(spec.count, 1.0);
    return out;
  }

  // Shrink, then grow: place all cells small, then move and grow them until full size.
  double scale = kStartScale;
  Packing cells = problem.add_sequentially(rng, scale);
  while (cells.size() < spec.count && scale > 0.1) {
    scale *= 0.5;
    cells = problem.add_sequentially(rng, scale);
  }
  int sweeps = 0;
  if (cells.size() == spec.count && hematocrit(spec.count, 1.0) < 1.0 && sequential.size() > 0) {
    double growth = kMaxGrowth, step = kMaxStep;
    for (int idle = 0; sweeps < kMaxSweeps && scale < 1.0 && idle < kPatience; ++sweeps) {
      const double accepted = problem.sweep(rng, cells, step);
      step = std::clamp(accepted < 0.3 ? 0.5 * step : accepted > 0.5 ? 2.0 * step : step, kMinStep, kMaxStep);
      Packing grown = cells;  // the same positions, so the same bins
      const double next = std::min(1.0, scale * (1.0 + growth));
      grown.set_scale(next);
      if (problem.separate(rng, grown, problem.touching(grown))) {
        cells = std::move(grown);
        scale = next;
        growth = std::min(kMaxGrowth, 1.5 * growth);
        idle = 0;
      } else {
        growth = std::max(kMinGrowth, 0.5 * growth);
        ++idle;
      }
    }
    if (scale >= 1.0) return finish(cells.cells(), sweeps);
  }
  std::string message = "cell placement: only " + std::to_string(sequential.size()) + " of " +
                        std::to_string(spec.count) + " cells fit (hematocrit " +
                        percent(hematocrit(static_cast<double>(sequential.size()), 1.0)) + " of the " +
                        percent(hematocrit(spec.count, 1.0)) + " requested) by random sequential addition";
  if (sequential.size() == 0)
    message.append("; not even one cell fits (the cell's largest diameter is " + percent(2.0 * overlap.radius()) + ")");
  else if (hematocrit(spec.count, 1.0) >= 1.0)
    message.append("; the cells' volume exceeds the space");
  else
    message.append(cells.size() == spec.count
                     ? "; compressing all of them from a smaller size stopped at " + percent(100.0 * scale) +
                           "% of full size after " + std::to_string(sweeps) + " sweeps"
                     : "; they do not fit even at " + percent(100.0 * scale) + "% of full size");
  message.append(" (gap " + percent(spec.gap) + "): lower the count or hematocrit, or enlarge the box");
  throw std::runtime_error(message);
}

namespace {

std::vector<SHSurface> surfaces(const SHSurface& reference, const std::vector<PlacedCell>& cells, bool stretched) {
  const Eigen::Vector3d centroid = volume_centroid(reference.geometry(SHTransform::gauss(2 * reference.order())));
  std::vector<SHSurface> out;
  for (const PlacedCell& c : cells) {
    SHSurface s = reference;
    s.transform(stretched ? Eigen::Matrix3d(c.stretch * c.rotation) : c.rotation, centroid);
    s.translate(c.position - centroid);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

std::vector<SHSurface> placed_surfaces(const SHSurface& reference, const std::vector<PlacedCell>& cells) {
  return surfaces(reference, cells, false);
}

std::vector<SHSurface> initial_surfaces(const SHSurface& reference, const Placement& placement) {
  if (!placement.parachute) return surfaces(reference, placement.cells, true);
  std::vector<SHSurface> out;
  for (const PlacedCell& c : placement.cells) {  // the parachute's centroid is at the origin
    SHSurface s = *placement.parachute;
    s.rotate(c.rotation);
    s.translate(c.position);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace rbcflow
