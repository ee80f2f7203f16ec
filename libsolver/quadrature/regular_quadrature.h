#pragma once
// The regular quadrature rule (30): I(x0) = sum_p K(x_p - x0) psi_p w_p over the Gauss grid
// nodes of the source surfaces, by direct summation (O(sources x targets); the periodic solver
// uses SPME instead). A source coinciding with its target (the same node) is skipped: its
// contribution belongs to the singular correction.
#include <Eigen/Core>

#include "libsolver/quadrature/layer_kernel.h"

namespace rbcflow {

// Source nodes of one or more surfaces: positions, area weights w_p and unit normals.
struct SourceNodes {
  Eigen::Matrix<double, Eigen::Dynamic, 3> x;
  Eigen::VectorXd weight;
  Eigen::Matrix<double, Eigen::Dynamic, 3> normal;
  int size() const { return static_cast<int>(x.rows()); }
};

// Targets x0 (rows); self[t] >= 0 names the source node that coincides with target t.
Eigen::MatrixXd regular_layer_sum(const SourceNodes& sources, const Eigen::MatrixXd& density,
                                  const LayerKernel& kernel, const Eigen::MatrixXd& targets,
                                  const std::vector<int>& self = {});

}  // namespace rbcflow
