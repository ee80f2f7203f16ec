#include "io/cell_layout.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>

#include "geometry/reference_shapes.h"

namespace rbcflow {
namespace {

constexpr int kCheckOrder = 8;

Eigen::Vector3d to_eigen(const Vec3& x) { return {x[0], x[1], x[2]}; }

std::string vec_text(const Eigen::Vector3d& x) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.4g, %.4g, %.4g]", x.x(), x.y(), x.z());
  return buf;
}

// Uniform double in [0, 1) from the top 53 bits: the same sequence with every standard library.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Generalised winding number of a closed outward mesh around p: 1 inside, 0 outside
// (Van Oosterom & Strackee's solid angle of each triangle).
double winding_number(const TriangleMesh& m, const Eigen::Vector3d& p) {
  double sum = 0;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Eigen::Vector3d a = m.points.row(m.triangles(t, 0)).transpose() - p;
    const Eigen::Vector3d b = m.points.row(m.triangles(t, 1)).transpose() - p;
    const Eigen::Vector3d c = m.points.row(m.triangles(t, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    sum += 2.0 * std::atan2(num, den);
  }
  return sum / (4.0 * std::numbers::pi);
}

bool any_point_inside(const TriangleMesh& points_of, const TriangleMesh& surface) {
  for (int p = 0; p < points_of.num_points(); ++p) {
    if (winding_number(surface, points_of.points.row(p).transpose()) > 0.5) return true;
  }
  return false;
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

void check_cell_layout(const Case& c) {
  if (!c.cells || c.cells->positions.empty()) return;
  const CaseCells& cells = *c.cells;
  const SHTransform t = SHTransform::gauss(kCheckOrder);
  std::vector<TriangleMesh> meshes;
  for (const SHSurface& s : placed_cells(cells, kCheckOrder)) meshes.push_back(s.triangulate(t));
  const int n = static_cast<int>(meshes.size());
  const bool periodic = c.domain.kind == DomainKind::periodic;
  const Eigen::Vector3d box = to_eigen(c.domain.box);
  auto fail = [&](const std::string& why) { throw case_error(c, "cells.positions", why); };

  std::vector<double> radius(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d centre = to_eigen(cells.positions[i]);
    radius[i] = (meshes[i].points.rowwise() - centre.transpose()).rowwise().norm().maxCoeff();
    if (!periodic) continue;
    const Eigen::Vector3d extent = meshes[i].points.colwise().maxCoeff() - meshes[i].points.colwise().minCoeff();
    for (int k = 0; k < 3; ++k) {
      if (extent[k] >= box[k]) {
        fail("cell " + std::to_string(i) + " is " + std::to_string(extent[k]) + " long along axis " +
             std::to_string(k) + ", longer than the periodic box (" + std::to_string(box[k]) + ")");
      }
    }
  }

  if (c.vessel && (c.vessel->kind == VesselKind::tube || c.vessel->kind == VesselKind::constriction)) {
    const CaseVessel& v = *c.vessel;
    const int a = v.axis, b1 = (a + 1) % 3, b2 = (a + 2) % 3;
    for (int i = 0; i < n; ++i) {
      for (int p = 0; p < meshes[i].num_points(); ++p) {
        const Eigen::Vector3d x = meshes[i].points.row(p).transpose();
        const double s = x[a] - box[a] * std::floor(x[a] / box[a]);
        const double d = v.kind == VesselKind::tube
                             ? v.diameter
                             : v.diameter - v.depth * std::exp(-v.width * (s - v.center) * (s - v.center));
        if (std::hypot(x[b1] - box[b1] / 2, x[b2] - box[b2] / 2) >= d / 2) {
          fail("cell " + std::to_string(i) + " at " + vec_text(to_eigen(cells.positions[i])) +
               " crosses the vessel wall (its surface reaches " + vec_text(x) + ")");
        }
      }
    }
  }

  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      Eigen::Vector3d d = to_eigen(cells.positions[j]) - to_eigen(cells.positions[i]);
      if (periodic) {
        for (int k = 0; k < 3; ++k) d[k] -= box[k] * std::round(d[k] / box[k]);
      }
      if (d.norm() >= radius[i] + radius[j]) continue;
      TriangleMesh other = meshes[j];
      const Eigen::Vector3d shift = to_eigen(cells.positions[i]) + d - to_eigen(cells.positions[j]);
      other.points.rowwise() += shift.transpose();
      if (any_point_inside(other, meshes[i]) || any_point_inside(meshes[i], other)) {
        fail("cells " + std::to_string(i) + " at " + vec_text(to_eigen(cells.positions[i])) + " and " +
             std::to_string(j) + " at " + vec_text(to_eigen(cells.positions[j])) + " overlap");
      }
    }
  }
}

}  // namespace rbcflow
