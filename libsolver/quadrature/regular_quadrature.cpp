#include "regular_quadrature.h"

#include <stdexcept>

namespace rbcflow {

Eigen::MatrixXd regular_layer_sum(const SourceNodes& sources, const Eigen::MatrixXd& density,
                                  const LayerKernel& kernel, const Eigen::MatrixXd& targets,
                                  const std::vector<int>& self) {
  if (density.rows() != sources.size() || density.cols() != 3 || targets.cols() != 3) {
    throw std::invalid_argument("regular_layer_sum: density must be (sources x 3), targets (n x 3)");
  }
  const int nt = static_cast<int>(targets.rows());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(nt, 3);
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t) {
    const Eigen::Vector3d x0 = targets.row(t);
    const int skip = self.empty() ? -1 : self[t];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int p = 0; p < sources.size(); ++p) {
      if (p == skip) continue;
      const Eigen::Vector3d r = Eigen::Vector3d(sources.x.row(p)) - x0;
      const Eigen::Vector3d m = sources.weight[p] * Eigen::Vector3d(sources.normal.row(p));
      const double w = kernel.layer() == Layer::single ? sources.weight[p] : 1.0;
      sum += w * (kernel.matrix(r, m) * Eigen::Vector3d(density.row(p)));
    }
    out.row(t) = sum;
  }
  return out;
}

}  // namespace rbcflow
