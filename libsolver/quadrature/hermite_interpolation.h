#pragma once
// Bicubic Hermite interpolation of spherical-harmonic fields on a uniform (theta, phi) grid
// (section 5.4): values and the derivatives f_theta, f_phi, f_theta_phi at the grid nodes
// come exactly from the expansion, and on each grid cell the field is the bicubic with that
// data. The grid includes both poles; f(theta, phi) is smooth on the parameter rectangle, so
// no pole needs special care. O(h^4) accurate.
#include <Eigen/Core>
#include <array>
#include <cassert>
#include <cstdint>
#include <memory>
#include <type_traits>

#include "geometry/sph/sph_transform.h"

namespace rbcflow {

// Node data, one row per grid node: column 4 c + d for component c and data type d = value,
// d/dtheta, d/dphi, d2/dtheta dphi. Row-major, so that the 4 k numbers a stencil corner reads
// are contiguous.
using HermiteData = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Where a point (theta, phi) falls on the uniform grid, with its Hermite weights in product
// form: the weight of corner (a, b) in {0,1}^2 and data type (d_theta, d_phi) is
// theta_w[2 a + d_theta] * phi_w[2 b + d_phi] (value and slope basis at each end).
// Trivial (no default values), so that large tables of stencils need no initialisation.
struct HermiteStencil {
  int i, j;  // the cell's (theta_i, phi_j) corner
  std::array<double, 4> theta_w;
  std::array<double, 4> phi_w;
};
// The same with its weights in single precision (40 bytes against 72), for the tables of patch
// points that many targets read (a ring of node targets): an interpolated value then carries a
// relative rounding error of ~1e-7, below the solver's tolerances (singular_quadrature.h).
struct FloatHermiteStencil {
  int i, j;
  std::array<float, 4> theta_w;
  std::array<float, 4> phi_w;
  static FloatHermiteStencil of(const HermiteStencil& s) {
    FloatHermiteStencil c{s.i, s.j, {}, {}};
    for (int k = 0; k < 4; ++k) {
      c.theta_w[k] = static_cast<float>(s.theta_w[k]);
      c.phi_w[k] = static_cast<float>(s.phi_w[k]);
    }
    return c;
  }
};
// The same for the large tables that one target reads (12 bytes against 72): the corner as 16-bit indices and the point's offsets in the cell, s and t in
// [0, 1], in single precision; the weights are computed from s and t as the stencil is read
// (a few flops against the 4 x 4 K multiply-adds of an interpolation). s and t carry an absolute
// rounding error of ~3e-8, so an interpolated value carries a relative error of ~1e-7, below
// the solver's tolerances (singular_quadrature.h).
struct CompactHermiteStencil {
  std::uint16_t i, j;
  float s, t;
};

// Cubic Hermite basis on [0, 1] for a cell of width h: value and slope weights at the left (0)
// and right (1) ends, in the order {value 0, slope 0, value 1, slope 1}.
template <class Real>
inline std::array<double, 4> hermite_weights(Real s_in, double h) {
  const double s = s_in, s2 = s * s, sm1 = s - 1.0, v1 = s2 * (3.0 - 2.0 * s);
  return {1.0 - v1, h * s * sm1 * sm1, v1, h * s2 * sm1};  // 1 - 3s^2 + 2s^3, h(s - 2s^2 + s^3), ...
}

class HermiteInterpolator {
 public:
  // Fields of order <= `order`, on a uniform grid of refinement r: (r N + 1) x 2 r N.
  HermiteInterpolator(int order, int refinement);

  int order() const { return transform_->order(); }
  int n_theta() const { return transform_->grid().n_theta(); }
  int n_phi() const { return transform_->grid().n_phi(); }

  // Node data of an expansion (grid size x 4 k).
  HermiteData node_data(const SHCoeffs& c) const;

  HermiteStencil stencil(double theta, double phi) const;
  // The same point as a CompactHermiteStencil. Throws std::length_error for a grid of more
  // than 65,536 nodes in theta or phi.
  CompactHermiteStencil compact_stencil(double theta, double phi) const;

  // The K interpolated components at a stencil (data.cols() == 4 K). phi_shift moves the
  // stencil by whole grid cells in phi (>= 0): the point (theta, phi + phi_shift * 2 pi / n_phi).
  // K is a compile-time constant so that the sums stay in registers: this runs for every patch
  // point of every GMRES product.
  // Stencil: HermiteStencil, FloatHermiteStencil or CompactHermiteStencil (whose weights are
  // computed here: a third more time per point than reading them).
  template <int K, typename Stencil, typename Out>
  void interpolate(const HermiteData& data, const Stencil& s, Out&& out, int phi_shift = 0) const {
    assert(data.cols() == 4 * K);
    const int np = n_phi();
    int j = s.j + phi_shift;  // no integer division
    while (j >= np) j -= np;
    const int j1 = j + 1 == np ? 0 : j + 1;
    const int nodes[4] = {s.i * np + j, s.i * np + j1, (s.i + 1) * np + j, (s.i + 1) * np + j1};
    // The 4 data types of a corner are one 4-wide packet: weight (theta_w[2a + d_theta] *
    // phi_w[2b + d_phi]) times data, summed over the corners, then across the packet.
    using Packet = Eigen::Array4d;
    std::array<double, 4> tw, pw;
    if constexpr (std::is_same_v<Stencil, CompactHermiteStencil>) {
      tw = hermite_weights(s.s, dtheta_);
      pw = hermite_weights(s.t, dphi_);
    } else {
      for (int k = 0; k < 4; ++k) {
        tw[k] = s.theta_w[k];
        pw[k] = s.phi_w[k];
      }
    }
    const Packet theta[2] = {{tw[0], tw[1], tw[0], tw[1]}, {tw[2], tw[3], tw[2], tw[3]}};
    const Packet phi[2] = {{pw[0], pw[0], pw[1], pw[1]}, {pw[2], pw[2], pw[3], pw[3]}};
    Packet sum[K];
    for (int c = 0; c < K; ++c) sum[c].setZero();
    for (int corner = 0; corner < 4; ++corner) {
      const double* row = data.data() + static_cast<std::size_t>(nodes[corner]) * (4 * K);
      const Packet w = theta[corner / 2] * phi[corner % 2];
      for (int c = 0; c < K; ++c) sum[c] += w * Eigen::Map<const Packet>(row + 4 * c);
    }
    for (int c = 0; c < K; ++c) out[c] = sum[c].sum();
  }

 private:
  std::shared_ptr<const SHTransform> transform_;
  double dtheta_, dphi_;
};

}  // namespace rbcflow
