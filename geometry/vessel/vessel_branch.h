#pragma once
// The branches of a vessel, where its flow and its cells are counted (branches.csv): straight
// pieces of centreline with a radius. A tube or constriction is one branch; a bifurcation three
// (0 the parent, 1 and 2 the daughters); a network one per segment. Each branch's mid
// cross-section is a disk of its radius about the middle of its centreline, normal to it: the
// positive flow direction is from `from` to `to`. Its flux may be measured through any
// cross-section of its clear part (the same flux at every instant).
#include <Eigen/Core>
#include <vector>

namespace rbcflow {

struct VesselBranch {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();  // may reach past a box face
  double radius = 0.0;
  // The part of the centreline, as fractions from `from` to `to`, whose cross-sections belong
  // to this branch alone (clear of junctions and bends): where its flux may be measured.
  double clear_from = 0.5, clear_to = 0.5;
  Eigen::Vector3d centre() const { return 0.5 * (from + to); }
  Eigen::Vector3d direction() const { return (to - from).normalized(); }
};

// The branch whose centreline (periodic images along `period` included) is nearest x, by the
// distance from it less its radius.
int nearest_branch(const std::vector<VesselBranch>& branches, const Eigen::Vector3d& x, const Eigen::Vector3d& period);

// A quadrature of the mid cross-section disk: radial Gauss-Legendre points (weight r dr) times
// equally spaced angles; exact for polynomials in the radius up to degree 2 radial - 1 times
// trigonometric ones in the angle below `angular`.
struct SectionQuadrature {
  Eigen::Matrix<double, Eigen::Dynamic, 3> points;
  Eigen::VectorXd weights;  // area weights, summing to pi r^2
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};
SectionQuadrature section_quadrature(const VesselBranch& branch, int radial = 8, int angular = 24);

// `count` cross-sections evenly spaced over the branch's clear part (one where it is a point),
// for section_flux.h's choice of the one farthest from the cells.
std::vector<SectionQuadrature> candidate_sections(const VesselBranch& branch, int count = 5);

}  // namespace rbcflow
