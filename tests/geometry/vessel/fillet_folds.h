#pragma once
// The vessel of `spec` built sharp and with fillet_radius = r (the tests of bifurcation and
// network fillets): the largest fold of the sharp wall, and the rounded wall with its quality.
#include <cstdio>

#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

struct FilletFolds {
  double sharp_fold_deg = 0.0;
  VesselMesh rounded;
  MeshQuality quality;
};

template <class Spec, class Build>
FilletFolds sharp_and_rounded(Spec spec, double r, Build build) {
  FilletFolds f;
  f.sharp_fold_deg = check_mesh(build(spec)).max_fold_deg;
  spec.fillet_radius = r;
  f.rounded = build(spec);
  f.quality = check_mesh(f.rounded);
  std::printf("largest fold between neighbouring triangles: sharp %.1f deg, fillet r = %.2f %.1f deg; %d nodes, "
              "min angle %.1f deg, edges %.4f..%.3f\n",
              f.sharp_fold_deg, r, f.quality.max_fold_deg, f.rounded.surface.num_points(), f.quality.min_angle_deg,
              f.quality.min_edge, f.quality.max_edge);
  return f;
}

}  // namespace rbcflow
