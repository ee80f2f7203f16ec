// rbcflow shape: export a reference cell shape (rbc, sphere, ellipsoid, squeezed-ellipsoid)
// as a triangulated .vtp surface with its curvatures, for a first look in ParaView.
#include <cstdio>
#include <string>

#include "cli.h"
#include "geometry/surface/reference_shapes.h"
#include "io/vtk_polydata.h"

namespace rbcflow::cli {

int run_shape(Args& args) {
  if (args.help_requested()) {
    std::printf(
        "usage: rbcflow shape rbc|sphere|ellipsoid|squeezed-ellipsoid [--order N] -o FILE.vtp\n"
        "  Writes the reference shape, spherical-harmonic order N (default 16), as a\n"
        "  triangulated surface with point data mean_curvature, gaussian_curvature, normal.\n");
    return 0;
  }
  const std::string kind = args.positional("shape name (rbc, sphere, ellipsoid, squeezed-ellipsoid)");
  std::string order_text = "16", out;
  args.option("--order", order_text);
  if (!args.option("-o", out)) throw UsageError("rbcflow shape: missing -o FILE.vtp");
  args.finish();
  int order = 0;
  try {
    order = std::stoi(order_text);
  } catch (const std::exception&) {
    throw UsageError("rbcflow shape: --order must be an integer, got '" + order_text + "'");
  }
  if (order < 4 || order > 128) {
    throw UsageError("rbcflow shape: --order must be in 4..128, got " + order_text);
  }
  SHSurface s;
  if (kind == "rbc") {
    s = make_biconcave(order);
  } else if (kind == "sphere") {
    s = make_sphere(order);
  } else if (kind == "ellipsoid") {
    s = make_ellipsoid(order, Eigen::Vector3d(0.8, 0.9, 1.0));
  } else if (kind == "squeezed-ellipsoid") {
    s = make_squeezed_ellipsoid(order, squeezed_ellipsoid_default_rotation());
  } else {
    throw UsageError("rbcflow shape: unknown shape '" + kind +
                     "' (expected rbc, sphere, ellipsoid or squeezed-ellipsoid)");
  }
  const SHTransform t = SHTransform::gauss(order);
  const SurfaceGeometry g = s.geometry(t);
  TriangleMesh mesh = s.triangulate(t);
  // The two pole points carry the values of the nearest ring (for display only).
  auto with_poles = [&](const Eigen::MatrixXd& grid_values) {
    Eigen::MatrixXd v(mesh.num_points(), grid_values.cols());
    v.topRows(grid_values.rows()) = grid_values;
    v.row(grid_values.rows()) = grid_values.row(0);
    v.row(grid_values.rows() + 1) = grid_values.row(grid_values.rows() - 1);
    return v;
  };
  write_vtp(out, mesh,
            {{"mean_curvature", with_poles(g.mean_curvature)},
             {"gaussian_curvature", with_poles(g.gaussian_curvature)},
             {"normal", with_poles(g.normal)}});
  std::printf("%s: order %d, area %.6f, volume %.6f -> %s\n", kind.c_str(), order, surface_area(g),
              enclosed_volume(g), out.c_str());
  return 0;
}

}  // namespace rbcflow::cli
