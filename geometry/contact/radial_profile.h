#pragma once
// The radial profile of the volume fraction that closed surfaces (the cells of a frame, merged
// into one triangle mesh) occupy in a straight periodic tube: the fraction of each annulus
// [r_i, r_i+1) about the axis, over one period, that lies inside the surfaces. Points sampled on
// a cylindrical grid (equal-area rings in each annulus, about `spacing` apart along and around
// the axis) are taken as inside when the closest triangle's outward normal faces away from them,
// the test of CellOverlap. Cells are not wrapped into the period as they move along the tube:
// each surface (the points of one `component`) is moved by whole periods so that the mean of
// its points lies in the period, and each sample point is also tried one period either way,
// for the surfaces that cross the period's ends. The sampling error is first order in `spacing`.
#include <Eigen/Core>
#include <vector>

#include "geometry/surface/triangle_mesh.h"

namespace rbcflow {

struct RadialProfileSpec {
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  int axis = 2;
  double radius = 0.0;  // of the tube: the annuli cover [0, radius)
  double period = 0.0;  // along the axis
  int bins = 20;
  double spacing = 0.1;
};

// `component`: the surface each point belongs to (0, 1, ...). Throws std::invalid_argument for
// an empty mesh, components that do not match the points, or a spec that is not positive.
std::vector<double> radial_volume_fraction(TriangleMesh surfaces, const Eigen::VectorXi& component,
                                           const RadialProfileSpec& spec);

}  // namespace rbcflow
