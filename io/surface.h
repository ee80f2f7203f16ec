#pragma once
// One surface of an output frame: a triangle mesh and named point fields. Every writer
// (VTK, XDMF) and the renderer take these. Cells are written as one surface ("cells", the
// cells' meshes merged with a `cell` index field); the wall as another ("wall").
#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/surface/triangle_mesh.h"

namespace rbcflow {

// A named field on the points of a mesh: one row per point, 1 (scalar), 3 (vector) or 9
// (tensor) columns.
struct SurfaceField {
  std::string name;
  Eigen::MatrixXd values;
};

struct Surface {
  std::string name;
  TriangleMesh mesh;
  std::vector<SurfaceField> fields;
};

// Throws std::invalid_argument when a name is empty or not [A-Za-z0-9_], a field name repeats,
// or a field's rows differ from the points.
void validate(const Surface& s);

// The parts as one surface: points and triangles concatenated, fields concatenated by name
// (every part must carry the same fields), and a scalar field `id_field` with each point's
// part index.
Surface merge_surfaces(const std::string& name, const std::vector<Surface>& parts,
                       const std::string& id_field = "cell");

}  // namespace rbcflow
