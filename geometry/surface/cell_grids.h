#pragma once
// The two grids of a cell of order N with de-aliasing order M (section 10): the N x 2N grid
// where the cell lives and the M x 2M grid where nonlinear terms are evaluated. Cells of the
// same (N, M) share one CellGrids.
#include <memory>

#include "geometry/sph/sph_transform.h"

namespace rbcflow {

struct CellGrids {
  int order = 0;          // N: degrees n < N
  int dealias_order = 0;  // M >= N
  std::shared_ptr<const SHTransform> n_grid;  // order N on N x 2N, theta derivatives <= 2
  std::shared_ptr<const SHTransform> m_grid;  // order M on M x 2M, theta derivatives <= 2

  static std::shared_ptr<const CellGrids> make(int order, int dealias_order);
};

}  // namespace rbcflow
