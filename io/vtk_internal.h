#pragma once
// VTK helpers shared inside io/ (the only header that exposes VTK types): surfaces as
// PolyData for the .vtp writer and the renderer, and a render window saved as PNG.
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>

#include <filesystem>

#include "io/surface.h"

namespace rbcflow {

// Points, triangles and one double array per field (point data; cell data for the triangle
// fields); throws std::invalid_argument when a field's rows differ from the points (triangles).
vtkSmartPointer<vtkPolyData> to_polydata(const TriangleMesh& mesh, const std::vector<SurfaceField>& fields,
                                         const std::vector<SurfaceField>& triangle_fields = {});

// Renders `window` and writes its image to `png` atomically.
void write_png(vtkRenderWindow* window, const std::filesystem::path& png);

}  // namespace rbcflow
