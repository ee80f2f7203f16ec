#include "geometry/vessel/crease_fillet.h"

#include <gmsh.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>
#include <vector>

#include "geometry/format_number.h"

namespace rbcflow {

namespace {

using DimTags = std::vector<std::pair<int, int>>;

// The largest angle between the normals of the two faces along a curve (sampled at a few points
// of it): 0 where the faces meet smoothly, the crease's angle where two fused solids meet.
double crease_angle(int curve, const std::vector<int>& faces) {
  std::vector<double> lo, hi;
  gmsh::model::getParametrizationBounds(1, curve, lo, hi);
  double largest = 0;
  for (double f : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    std::vector<double> x;
    gmsh::model::getValue(1, curve, {lo[0] + f * (hi[0] - lo[0])}, x);
    Eigen::Vector3d n[2];
    for (int k = 0; k < 2; ++k) {
      std::vector<double> uv, nk;
      gmsh::model::getParametrization(2, faces[k], x, uv);
      gmsh::model::getNormal(faces[k], uv, nk);
      n[k] = Eigen::Vector3d(nk[0], nk[1], nk[2]).normalized();
    }
    largest = std::max(largest, std::acos(std::clamp(std::abs(n[0].dot(n[1])), 0.0, 1.0)));
  }
  return largest;
}

}  // namespace

std::pair<int, int> round_creases(std::pair<int, int> lumen, double radius, double length, const std::string& what) {
  namespace occ = gmsh::model::occ;
  DimTags faces, curves;
  gmsh::model::getBoundary({lumen}, faces, false, false, false);
  gmsh::model::getBoundary(faces, curves, false, false, false);
  std::set<int> lumen_faces, seen;
  for (const auto& face : faces) lumen_faces.insert(std::abs(face.second));
  std::vector<int> creases;
  for (const auto& curve : curves) {
    const int tag = std::abs(curve.second);
    if (!seen.insert(tag).second) continue;
    // The lumen's faces on the curve (the model may hold others: a revolve's profile).
    std::vector<int> adjacent, on_lumen, down;
    gmsh::model::getAdjacencies(1, tag, adjacent, down);
    for (int f : adjacent)
      if (lumen_faces.count(f)) on_lumen.push_back(f);
    double xmin, ymin, zmin, xmax, ymax, zmax;
    gmsh::model::getBoundingBox(1, tag, xmin, ymin, zmin, xmax, ymax, zmax);
    // OpenCASCADE pads bounding boxes by its tolerance (1e-7).
    const bool in_box_face = zmax < 1e-6 * length || zmin > (1 - 1e-6) * length;
    if (on_lumen.size() == 2 && !in_box_face && crease_angle(tag, on_lumen) > 5 * std::numbers::pi / 180)
      creases.push_back(tag);
  }
  if (creases.empty()) return lumen;
  DimTags rounded;
  occ::fillet({lumen.second}, creases, {radius}, rounded, true);
  if (rounded.size() != 1 || rounded[0].first != 3)
    throw std::runtime_error("gmsh (OpenCASCADE) could not round " + what + "'s " + std::to_string(creases.size()) +
                             " junction edges with fillet_radius " + format_number(radius) +
                             "; the radius must fit the junction: try a smaller or a slightly different one");
  occ::synchronize();
  return rounded[0];
}

}  // namespace rbcflow
