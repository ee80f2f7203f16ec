#include "cell_halo.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/surface/sh_surface.h"

namespace rbcflow {

CellSphere bounding_sphere(const Eigen::MatrixXd& nodes) {
  if (nodes.rows() == 0 || nodes.cols() != 3) throw std::invalid_argument("bounding_sphere: no nodes");
  CellSphere s;
  for (int k = 0; k < 3; ++k) s.center[k] = nodes.col(k).mean();
  s.radius = (nodes.rowwise() - s.center.transpose()).rowwise().norm().maxCoeff();
  return s;
}

CellSphere cell_sphere(const SHCoeffs& shape, const CellGrids& grids) {
  // The geometry the cell's layers take (CellQuadratureGeometry): the same nodes and area.
  const SurfaceGeometry g = surface_geometry(shape.resampled(grids.order), *grids.n_grid);
  CellSphere s = bounding_sphere(g.x);
  s.area = surface_area(g);
  return s;
}

std::optional<SlabPlanes> rank_slab(const SpmeGrid& grid) {
  if (!grid.distributed()) return std::nullopt;
  return SlabPlanes{grid.axis(0), grid.size(0), grid.first_plane(), grid.planes(), grid.order()};
}

bool reaches_slab(const CellSphere& sphere, const SlabPlanes& slab, const PeriodicBox& box) {
  const int K = slab.size;
  const double scale = K / box.length(slab.axis);
  // The lowest and highest stencil planes of the nodes within the sphere, unwrapped, one more
  // each side for the rounding of a coordinate wrapped into the box (spme_stencils.cpp).
  const long low = static_cast<long>(std::floor((sphere.center[slab.axis] - sphere.radius) * scale)) - slab.order;
  const long high = static_cast<long>(std::floor((sphere.center[slab.axis] + sphere.radius) * scale)) + 1;
  if (high - low + 1 >= K) return true;
  const long first = ((low % K) + K) % K;  // the stencils' planes are first .. first + (high - low), modulo K
  for (long k = first; k <= first + (high - low); ++k) {
    const long plane = k % K;
    if (slab.first_plane <= plane && plane < slab.first_plane + slab.planes) return true;
  }
  return false;
}

namespace {

// The distance between a and b at b's periodic image nearest a.
double nearest_image_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const PeriodicBox& box) {
  Eigen::Vector3d d = b - a;
  for (int k = 0; k < 3; ++k) d[k] -= box.length(k) * std::round(d[k] / box.length(k));
  return d.norm();
}

}  // namespace

std::vector<int> cell_halo(const std::vector<CellSphere>& spheres, OwnedRange owned, const std::optional<PeriodicBox>& box,
                           double reach, const std::vector<SlabPlanes>& slabs) {
  const int n = static_cast<int>(spheres.size());
  if (owned.begin < 0 || owned.end > n || owned.end < owned.begin)
    throw std::invalid_argument("cell_halo: the owned cells are not a range of the cells");
  std::vector<int> halo;
  for (int c = 0; c < n; ++c) {
    if (owned.contains(c)) continue;
    bool in = !box || slabs.empty();
    for (const SlabPlanes& slab : slabs) in = in || reaches_slab(spheres[c], slab, *box);
    for (int o = owned.begin; !in && o < owned.end; ++o)
      in = nearest_image_distance(spheres[o].center, spheres[c].center, *box) <= spheres[o].radius + spheres[c].radius + reach;
    if (in) halo.push_back(c);
  }
  return halo;
}

HaloExtent layers_halo_extent(double near_reach, const SpmeGrid* single_grid, const SpmeGrid* double_grid) {
  HaloExtent extent;
  extent.reach = near_reach;
  for (const SpmeGrid* grid : {single_grid, double_grid}) {
    if (!grid) continue;
    extent.reach = std::max(extent.reach, grid->parameters().cutoff);
    if (const std::optional<SlabPlanes> slab = rank_slab(*grid)) {
      extent.slabs.push_back(*slab);
    } else {
      extent.every_cell = true;  // a grid every rank holds whole: this rank's smooth part reaches every node
    }
  }
  if (!single_grid) extent.every_cell = true;  // free space: direct sums at every node
  return extent;
}

std::vector<int> cell_halo(const std::vector<CellSphere>& spheres, OwnedRange owned, const std::optional<PeriodicBox>& box,
                           const HaloExtent& extent, const std::vector<SlabPlanes>& other_slabs) {
  std::vector<SlabPlanes> slabs;
  if (!extent.every_cell) {
    slabs = extent.slabs;
    slabs.insert(slabs.end(), other_slabs.begin(), other_slabs.end());
  }
  return cell_halo(spheres, owned, box, extent.reach, slabs);
}

}  // namespace rbcflow
