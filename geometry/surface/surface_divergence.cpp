#include "geometry/surface/surface_divergence.h"

#include <stdexcept>

namespace rbcflow {

void contravariant_tangents(const SurfaceGeometry& g, SurfaceGeometry::Field3& up1,
                            SurfaceGeometry::Field3& up2) {
  const Eigen::ArrayXd det = g.a11.array() * g.a22.array() - g.a12.array().square();
  const Eigen::ArrayXd i11 = g.a22.array() / det, i12 = -g.a12.array() / det, i22 = g.a11.array() / det;
  up1 = g.a1.array().colwise() * i11 + g.a2.array().colwise() * i12;
  up2 = g.a1.array().colwise() * i12 + g.a2.array().colwise() * i22;
}

Eigen::MatrixXd surface_divergence(const Eigen::MatrixXd& T, const SurfaceGeometry& g,
                                   const SHTransform& t) {
  if (T.cols() != 9 || T.rows() != g.size() || g.size() != t.grid().size()) {
    throw std::invalid_argument("surface_divergence: need a (grid size x 9) tensor field on the transform's grid");
  }
  const SHCoeffs c = t.analyze(T);
  const Eigen::MatrixXd d1 = t.synthesize(c, 1, 0), d2 = t.synthesize(c, 0, 1);
  SurfaceGeometry::Field3 up1, up2;
  contravariant_tangents(g, up1, up2);
  Eigen::MatrixXd div = Eigen::MatrixXd::Zero(g.size(), 3);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      div.col(j).array() += up1.col(i).array() * d1.col(3 * i + j).array() +
                            up2.col(i).array() * d2.col(3 * i + j).array();
    }
  }
  return div;
}

}  // namespace rbcflow
