#pragma once
// VTK XML PolyData (.vtp) output of triangle meshes with point data, for ParaView.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/surface/triangle_mesh.h"
#include "io/surface.h"

namespace rbcflow {

// Writes `mesh` and its point fields as a binary, compressed .vtp file (atomically).
void write_vtp(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::vector<SurfaceField>& fields = {});

// Reads the points and triangles of a .vtp file (non-triangle cells are an error).
TriangleMesh read_vtp(const std::filesystem::path& path);
// The same with every point-data array, as a surface called `name`.
Surface read_vtp_surface(const std::filesystem::path& path, const std::string& name);

}  // namespace rbcflow
