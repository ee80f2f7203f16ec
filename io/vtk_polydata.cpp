#include "vtk_polydata.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <stdexcept>

#include "atomic_file.h"
#include "vtk_internal.h"

namespace rbcflow {

namespace {

vtkSmartPointer<vtkDataArray> to_array(const SurfaceField& f, int rows, const char* what) {
  if (f.values.rows() != rows) {
    throw std::invalid_argument("write_vtp: field '" + f.name + "' has " + std::to_string(f.values.rows()) +
                                " rows for " + std::to_string(rows) + " " + what);
  }
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(f.name.c_str());
  array->SetNumberOfComponents(static_cast<int>(f.values.cols()));
  array->SetNumberOfTuples(rows);
  for (int p = 0; p < rows; ++p) {
    for (int c = 0; c < f.values.cols(); ++c) array->SetComponent(p, c, f.values(p, c));
  }
  return array;
}

}  // namespace

vtkSmartPointer<vtkPolyData> to_polydata(const TriangleMesh& mesh, const std::vector<SurfaceField>& fields,
                                         const std::vector<SurfaceField>& triangle_fields) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.num_points());
  for (int p = 0; p < mesh.num_points(); ++p) {
    points->SetPoint(p, mesh.points(p, 0), mesh.points(p, 1), mesh.points(p, 2));
  }
  vtkNew<vtkCellArray> cells;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const vtkIdType ids[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    cells->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  for (const SurfaceField& f : fields) poly->GetPointData()->AddArray(to_array(f, mesh.num_points(), "points"));
  for (const SurfaceField& f : triangle_fields)
    poly->GetCellData()->AddArray(to_array(f, mesh.num_triangles(), "triangles"));
  return poly;
}

void write_vtp(const std::filesystem::path& path, const TriangleMesh& mesh, const std::vector<SurfaceField>& fields,
               const std::vector<SurfaceField>& triangle_fields) {
  const vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh, fields, triangle_fields);
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(poly);
    writer->SetDataModeToBinary();
    if (writer->Write() != 1) throw std::runtime_error("cannot write " + path.string());
  });
}

namespace {

// The reader's output; throws naming the file when it is not PolyData with points.
vtkSmartPointer<vtkPolyData> read_polydata(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw std::runtime_error("cannot read " + path.string() + ": no such file");
  }
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> poly = reader->GetOutput();
  if (!poly || poly->GetNumberOfPoints() == 0) {
    throw std::runtime_error("cannot read " + path.string() + ": not a VTK PolyData file with points");
  }
  return poly;
}

TriangleMesh mesh_of(vtkPolyData* poly, const std::filesystem::path& path) {
  TriangleMesh mesh;
  mesh.points.resize(poly->GetNumberOfPoints(), 3);
  for (vtkIdType p = 0; p < poly->GetNumberOfPoints(); ++p) {
    double x[3];
    poly->GetPoint(p, x);
    mesh.points.row(p) << x[0], x[1], x[2];
  }
  vtkCellArray* polys = poly->GetPolys();
  mesh.triangles.resize(polys->GetNumberOfCells(), 3);
  vtkNew<vtkIdList> ids;
  polys->InitTraversal();
  for (int t = 0; polys->GetNextCell(ids); ++t) {
    if (ids->GetNumberOfIds() != 3) {
      throw std::runtime_error("cannot read " + path.string() + ": cell " + std::to_string(t) +
                               " is not a triangle");
    }
    mesh.triangles.row(t) << ids->GetId(0), ids->GetId(1), ids->GetId(2);
  }
  return mesh;
}

}  // namespace

TriangleMesh read_vtp(const std::filesystem::path& path) { return mesh_of(read_polydata(path), path); }

Surface read_vtp_surface(const std::filesystem::path& path, const std::string& name) {
  const vtkSmartPointer<vtkPolyData> poly = read_polydata(path);
  Surface s{name, mesh_of(poly, path), {}};
  vtkPointData* data = poly->GetPointData();
  for (int a = 0; a < data->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = data->GetArray(a);
    if (!array || !array->GetName()) continue;
    Eigen::MatrixXd values(array->GetNumberOfTuples(), array->GetNumberOfComponents());
    for (vtkIdType p = 0; p < array->GetNumberOfTuples(); ++p) {
      for (int c = 0; c < array->GetNumberOfComponents(); ++c) values(p, c) = array->GetComponent(p, c);
    }
    s.fields.push_back({array->GetName(), values});
  }
  return s;
}

Eigen::MatrixXd read_vtp_triangle_field(const std::filesystem::path& path, const std::string& name) {
  const vtkSmartPointer<vtkPolyData> poly = read_polydata(path);
  vtkDataArray* array = poly->GetCellData()->GetArray(name.c_str());
  if (!array) throw std::runtime_error("cannot read " + path.string() + ": no triangle field '" + name + "'");
  Eigen::MatrixXd values(array->GetNumberOfTuples(), array->GetNumberOfComponents());
  for (vtkIdType p = 0; p < array->GetNumberOfTuples(); ++p) {
    for (int c = 0; c < array->GetNumberOfComponents(); ++c) values(p, c) = array->GetComponent(p, c);
  }
  return values;
}

}  // namespace rbcflow
