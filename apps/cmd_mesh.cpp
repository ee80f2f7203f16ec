// rbcflow mesh: build the vessel of a case with gmsh, check it, write WALL.msh (the mesh a
// `file` vessel reads back) and WALL.vtp beside it (for ParaView).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "scenario/vessel.h"
#include "cli.h"
#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"
#include "geometry/vessel/vessel.h"
#include "io/case.h"
#include "io/vtk_polydata.h"

namespace rbcflow::cli {
namespace {

namespace fs = std::filesystem;

// Fails before the (possibly long) meshing when the output cannot be written.
void check_writable(const fs::path& out) {
  const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) throw std::runtime_error("cannot write " + out.string() + ": " + dir.string() +
                                                       " is not a directory");
}

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

}  // namespace

int run_mesh(Args& args) {
  if (args.help_requested()) {
    std::printf(
        "usage: rbcflow mesh CASE.toml -o WALL.msh\n"
        "  Builds the [vessel] of the case with gmsh (tube, constriction, bifurcation, or a\n"
        "  .msh/.stl/.step/.iges file), runs the mesh checks (closed, manifold, consistently\n"
        "  oriented with normals into the lumen, no duplicate nodes), prints the node and\n"
        "  triangle counts and the minimum angle, and writes WALL.msh and WALL.vtp beside it\n"
        "  (with the branch of each triangle, as branches.csv numbers them).\n"
        "  Exit status 2 for a bad case or a vessel that cannot be built, 1 when the files\n"
        "  cannot be written.\n");
    return 0;
  }
  std::string out;
  if (!args.option("-o", out) && !args.option("--output", out)) throw UsageError("rbcflow mesh: missing -o WALL.msh");
  const std::string file = args.positional("case file (CASE.toml)");
  args.finish();
  const fs::path msh(out);
  if (msh.extension() != ".msh") throw UsageError("rbcflow mesh: -o must name a .msh file, got '" + out + "'");
  const Case c = read_case(file);
  check_writable(msh);

  const auto start = std::chrono::steady_clock::now();
  const VesselMesh wall = build_vessel(c);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const MeshQuality q = check_mesh(wall);
  int periodic = 0;
  for (int d = 0; d < 3; ++d) periodic += wall.period[d] > 0;
  const double volume = -lumen_flux(wall) / (3 - periodic);  // mesh_orientation.h

  const CaseVessel& v = *c.vessel;
  std::printf("case:    %s: \"%s\"\n", file.c_str(), c.title.c_str());
  std::printf("vessel:  %s along %s, element size %g\n", to_string(v.kind).c_str(), axis_name(v.axis),
              v.element_size);
  std::printf("mesh:    %d nodes, %d triangles (%.2f s)\n", wall.surface.num_points(), wall.surface.num_triangles(),
              seconds);
  std::printf("quality: min angle %.1f deg, edges %.3g..%.3g, largest fold %.1f deg, area %.4g, lumen volume %.4g\n",
              q.min_angle_deg, q.min_edge, q.max_edge, q.max_fold_deg, q.area, volume);
  write_vessel(wall, msh.string());
  fs::path vtp = msh;
  vtp.replace_extension(".vtp");
  // The branch of each triangle (nearest centreline, vessel_branch.h), for colouring in ParaView.
  const std::vector<VesselBranch> branches = vessel_branches(c);
  std::vector<SurfaceField> triangle_fields;
  if (!branches.empty()) {
    Eigen::MatrixXd branch(wall.surface.num_triangles(), 1);
    for (int t = 0; t < wall.surface.num_triangles(); ++t) {
      const Eigen::Vector3d centroid = triangle_vertices(wall, t).rowwise().mean();
      branch(t, 0) = nearest_branch(branches, centroid, wall.period);
    }
    triangle_fields.push_back({"branch", branch});
    std::printf("branches: %zu (the triangles' field `branch` in the .vtp)\n", branches.size());
  }
  write_vtp(vtp, drawable_surface(wall), {}, triangle_fields);
  std::printf("wrote:   %s, %s\n", msh.string().c_str(), vtp.string().c_str());
  return 0;
}

}  // namespace rbcflow::cli
