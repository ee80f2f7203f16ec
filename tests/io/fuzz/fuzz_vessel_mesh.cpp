// libFuzzer target for the checks every vessel mesh passes before a solve (geometry/
// mesh_check.h, mesh_orientation.h): whatever triangle soup gmsh or a file hands over — bad
// indices, repeated or collinear nodes, holes, non-manifold edges, NaN coordinates — orienting
// and checking it either succeeds or throws std::runtime_error / std::invalid_argument; it never
// crashes, hangs or trips a sanitizer. The input: 1 byte of periodic axes, 1 byte of point count,
// then 3 coordinates per point (int8 / 16, so that coincident and collinear nodes are common),
// then triangles as 3 bytes of node indices each (an index past the last node stays: a bad index).
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  rbcflow::VesselMesh wall;
  for (int k = 0; k < 3; ++k) wall.period[k] = (data[0] >> k) & 1 ? 4.0 : 0.0;
  const int n = data[1] % 64;
  std::size_t at = 2;
  if (size < at + 3 * static_cast<std::size_t>(n)) return 0;
  wall.surface.points.resize(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) wall.surface.points(i, k) = static_cast<std::int8_t>(data[at++]) / 16.0;
  const int t = static_cast<int>((size - at) / 3);
  wall.surface.triangles.resize(t, 3);
  for (int i = 0; i < t; ++i)
    for (int k = 0; k < 3; ++k) wall.surface.triangles(i, k) = data[at++];
  try {
    rbcflow::check_mesh(wall);  // bad input must be refused before orientation walks it
    rbcflow::orient_into_lumen(wall);
    rbcflow::check_mesh(wall);
    (void)rbcflow::lumen_flux(wall);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
