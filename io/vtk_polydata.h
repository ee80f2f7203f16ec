#pragma once
// VTK XML PolyData (.vtp) output of triangle meshes with point data, for ParaView.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/surface/triangle_mesh.h"
#include "io/surface.h"

namespace rbcflow {

// Writes `mesh` and its point fields (and fields on its triangles, VTK's cell data) as a
// binary, compressed .vtp file (atomically).
void write_vtp(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::vector<SurfaceField>& fields = {}, const std::vector<SurfaceField>& triangle_fields = {});

// The named array of the triangles' (cell) data of a .vtp file, one row per triangle; throws
// naming the file and the field when it is absent.
Eigen::MatrixXd read_vtp_triangle_field(const std::filesystem::path& path, const std::string& name);

// Reads the points and triangles of a .vtp file (non-triangle cells are an error).
TriangleMesh read_vtp(const std::filesystem::path& path);
// The same with every point-data array, as a surface called `name`.
Surface read_vtp_surface(const std::filesystem::path& path, const std::string& name);

}  // namespace rbcflow
