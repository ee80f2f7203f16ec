#include "scenario/cell_layout.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "geometry/contact/cell_overlap.h"
#include "geometry/contact/cell_placement.h"
#include "geometry/surface/reference_shapes.h"
#include "geometry/contact/wall_distance.h"

namespace rbcflow {
namespace {

constexpr double kMinimumPlacementGap = 0.05;

Eigen::Vector3d to_eigen(const Vec3& x) { return {x[0], x[1], x[2]}; }

std::string vec_text(const Eigen::Vector3d& x) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.4g, %.4g, %.4g]", x.x(), x.y(), x.z());
  return buf;
}

std::string fixed(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  return buf;
}

// Uniform double in [0, 1) from the top 53 bits: the same sequence with every standard library.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// The perturbation of section 9 added to a cell: amplitude Y_lm n, with Y_lm the real
// spherical harmonic of unit mean square on the sphere (m < 0: sin(|m| phi)) and n the
// outward normal of the cell.
void perturb(SHSurface& s, const CasePerturbation& p) {
  const int order = s.coeffs().order();
  const SHTransform t = SHTransform::gauss(order);
  SHCoeffs y(order, 1);
  if (p.m >= 0) {
    y.a(p.l, p.m) = 1.0;
  } else {
    y.b(p.l, -p.m) = 1.0;
  }
  Eigen::VectorXd Y = t.synthesize(y).col(0);
  double mean_square = 0;
  for (int q = 0; q < t.grid().size(); ++q) mean_square += t.grid().sphere_weight(q) * Y[q] * Y[q];
  Y /= std::sqrt(mean_square / (4 * std::numbers::pi));
  const SurfaceGeometry g = s.geometry(t);
  const Eigen::MatrixXd shift = (p.amplitude * Y).asDiagonal() * g.normal;
  s.coeffs().values() += t.analyze(shift, order).values();
}

// Cells placed at random without overlap (a count, or the tube hematocrit of the meshed
// lumen), placement_gap apart and from the wall; in tubes narrower than the cell, stacked
// and pre-deformed (geometry/contact/cell_placement.h).
InitialCells random_cells(const Case& c, const VesselMesh* vessel) {
  const CaseCells& k = *c.cells;
  if (c.domain.kind != DomainKind::periodic) {
    throw case_error(c, "cells.positions", "cells in a free domain must be listed (positions = [[x, y, z], ...])");
  }
  const SHSurface reference = reference_shape(k, k.order);
  int count = k.count.value_or(0);
  if (k.hematocrit) {
    if (!vessel) throw case_error(c, "cells.hematocrit", "a hematocrit needs a vessel");
    const double cell_volume = enclosed_volume(reference.geometry(SHTransform::gauss(k.order)));
    count = std::max(1, static_cast<int>(std::lround(*k.hematocrit * lumen_volume(*vessel) / cell_volume)));
  }
  PlacementSpec spec;
  spec.box = to_eigen(c.domain.box);
  spec.count = count;
  spec.gap = placement_gap(c);
  spec.seed = static_cast<std::uint64_t>(k.seed);
  spec.narrow_start = k.narrow_start == NarrowStartKind::parachute ? NarrowStart::parachute : NarrowStart::stretched;
  if (c.domain.mean_velocity) spec.flow = to_eigen(*c.domain.mean_velocity);
  if (c.domain.tube_velocity && c.vessel) spec.flow = *c.domain.tube_velocity * Eigen::Vector3d::Unit(c.vessel->axis);
  Placement p;
  try {
    p = place_cells(reference, spec, vessel);
  } catch (const std::runtime_error& e) {
    throw case_error(c, k.hematocrit ? "cells.hematocrit" : "cells.count", e.what());
  }
  InitialCells out{placed_surfaces(reference, p.cells), initial_surfaces(reference, p), std::nullopt};
  if (p.parachute) {
    out.note = "cells: the tube is narrower than a cell; placed stacked along the axis, folded face-on into "
               "parachutes (radius " + fixed(p.parachute_radius) + ", length " + fixed(p.parachute_length) +
               "; area and volume kept, the membranes' rest shape undeformed)";
  } else if (p.stretch_factors != Eigen::Vector3d::Ones()) {
    const Eigen::Vector3d& f = p.stretch_factors;
    out.note = "cells: the tube is narrower than a cell; placed stacked along the axis, pre-deformed (stretched " +
               fixed(f[0]) + " along the axis, " + fixed(f[1]) + " across, " + fixed(f[2]) +
               " through the thickness; volume kept, the membranes' rest shape undeformed)";
  }
  return out;
}

// The cells as they start, each a body of its own: inside the wall by h_s, inside the box (no
// cell meets its own periodic image), and apart from each other by h_s. `where` names
// each cell in the messages (its listed position or its centroid).
void check_cells(const Case& c, const std::vector<SHSurface>& cells, const std::vector<Eigen::Vector3d>& where,
                 const VesselMesh* vessel) {
  const bool periodic = c.domain.kind == DomainKind::periodic;
  const Eigen::Vector3d period = periodic ? to_eigen(c.domain.box) : Eigen::Vector3d::Zero();
  std::unique_ptr<WallDistance> wall;
  if (vessel) wall = std::make_unique<WallDistance>(*vessel);
  const double gap = c.time.collision_threshold;
  const CellOverlap overlap(cells, PlacementSpec{}.check_order, period, wall.get(), gap);
  const int n = static_cast<int>(cells.size());
  std::vector<CellPose> poses(n);
  for (int i = 0; i < n; ++i) poses[i] = CellPose{overlap.centroid(i), Eigen::Matrix3d::Identity(), 1.0, i};
  auto fail = [&](const std::string& why) { throw case_error(c, "cells.positions", why); };
  auto cell = [&](int i) { return std::to_string(i) + " at " + vec_text(where[i]); };
  char within[96] = "";
  if (gap > 0) std::snprintf(within, sizeof within, " (or within the collision threshold %g)", gap);

  for (int i = 0; i < n; ++i) {
    if (!overlap.inside_wall(poses[i])) fail("cell " + cell(i) + " crosses the vessel wall" + within);
    if (periodic) {
      const Eigen::MatrixXd& x = overlap.mesh(i).points;
      const Eigen::Vector3d extent = x.colwise().maxCoeff() - x.colwise().minCoeff();
      for (int k = 0; k < 3; ++k) {
        if (extent[k] >= period[k]) {
          fail("cell " + cell(i) + " is " + std::to_string(extent[k]) + " long along axis " + std::to_string(k) +
               ", longer than the periodic box (" + std::to_string(period[k]) + ")");
        }
      }
      if (!overlap.apart(poses[i], poses[i], true)) fail("cell " + cell(i) + " overlaps its own periodic image");
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (!overlap.apart(poses[i], poses[j])) fail("cells " + cell(i) + " and " + cell(j) + " overlap" + within);
    }
  }
}

}  // namespace

SHSurface reference_shape(const CaseCells& cells, int order) {
  switch (cells.shape) {
    case CellShape::rbc: return make_biconcave(order);
    case CellShape::sphere: return make_sphere(order);
    case CellShape::ellipsoid: return make_ellipsoid(order, to_eigen(cells.semi_axes));
  }
  return {};
}

std::vector<Vec3> cell_orientations(const CaseCells& cells) {
  std::vector<Vec3> axes;
  if (!cells.orientations.empty()) {
    for (const Vec3& o : cells.orientations) {
      const Eigen::Vector3d u = to_eigen(o).normalized();
      axes.push_back({u.x(), u.y(), u.z()});
    }
    return axes;
  }
  std::mt19937_64 rng(static_cast<std::uint64_t>(cells.seed));
  for (std::size_t i = 0; i < cells.positions.size(); ++i) {
    const double z = 2.0 * uniform(rng) - 1.0, phi = 2.0 * std::numbers::pi * uniform(rng);
    const double r = std::sqrt(1.0 - z * z);
    axes.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  return axes;
}

std::vector<SHSurface> placed_cells(const CaseCells& cells, int order) {
  const SHSurface shape = reference_shape(cells, order);
  const std::vector<Vec3> axes = cell_orientations(cells);
  std::vector<SHSurface> placed;
  for (std::size_t i = 0; i < cells.positions.size(); ++i) {
    SHSurface s = shape;
    const Eigen::Matrix3d turn =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), to_eigen(axes[i])).toRotationMatrix();
    s.rotate(turn);
    s.translate(to_eigen(cells.positions[i]));
    placed.push_back(std::move(s));
  }
  return placed;
}

double placement_gap(const Case& c) { return std::max(c.time.collision_threshold, kMinimumPlacementGap); }

InitialCells initial_cells(const Case& c, const VesselMesh* vessel) {
  const CaseCells& k = *c.cells;
  InitialCells cells;
  if (k.positions.empty()) {
    cells = random_cells(c, vessel);
  } else {
    cells.rest = placed_cells(k, k.order);
    cells.initial = cells.rest;
  }
  if (k.perturbation) {
    for (SHSurface& s : cells.initial) perturb(s, *k.perturbation);
  }
  // Random placement has checked its unperturbed cells, at placement_gap.
  if (k.positions.empty() && !k.perturbation) return cells;
  std::vector<Eigen::Vector3d> where;
  for (const SHSurface& s : cells.initial) where.push_back(volume_centroid(s.geometry(SHTransform::gauss(k.order))));
  for (std::size_t i = 0; i < k.positions.size(); ++i) where[i] = to_eigen(k.positions[i]);
  check_cells(c, cells.initial, where, vessel);
  return cells;
}

}  // namespace rbcflow
