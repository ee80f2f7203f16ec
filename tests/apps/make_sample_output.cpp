// Writes an output directory shaped like a run's, for the command-line tests of `render`
// until `rbcflow run` exists: case.toml, diagnostics.csv, cells.csv, the XDMF and VTK series
// of three frames in which the case's listed cells drift along the flow axis by <u> t inside
// a tube mesh. The fields are placeholders of the right shapes (velocity = <u>, force = 0,
// tension = 0, J_S = 1) plus the true mean curvature of each cell.
//   make_sample_output CASE.toml OUTDIR
#include <cmath>
#include <cstdio>
#include <numbers>

#include "io/case.h"
#include "io/csv.h"
#include "io/output_dir.h"
#include "io/vtk_series.h"
#include "io/xdmf_writer.h"
#include "scenario/cell_layout.h"
#include "scenario/derived.h"

using namespace rbcflow;

namespace {

// The tube of the case's vessel: a triangulated cylinder over one period of the box.
Surface tube_wall(const Case& c) {
  const CaseVessel& v = *c.vessel;
  const int a = v.axis, b = (a + 1) % 3, d = (a + 2) % 3;
  const double length = c.domain.box[a];
  const int around = 48, along = std::max(4, static_cast<int>(length / v.element_size));
  Surface wall{"wall", {}, {}};
  wall.mesh.points.resize(around * (along + 1), 3);
  for (int k = 0; k <= along; ++k) {
    for (int j = 0; j < around; ++j) {
      const double phi = 2 * std::numbers::pi * j / around;
      Eigen::RowVector3d x;
      x[a] = length * k / along;
      x[b] = c.domain.box[b] / 2 + v.diameter / 2 * std::cos(phi);
      x[d] = c.domain.box[d] / 2 + v.diameter / 2 * std::sin(phi);
      wall.mesh.points.row(k * around + j) = x;
    }
  }
  wall.mesh.triangles.resize(2 * around * along, 3);
  for (int k = 0; k < along; ++k) {
    for (int j = 0; j < around; ++j) {
      const int p = k * around + j, q = k * around + (j + 1) % around;
      wall.mesh.triangles.row(2 * (k * around + j)) << p, q + around, q;
      wall.mesh.triangles.row(2 * (k * around + j) + 1) << p, p + around, q + around;
    }
  }
  wall.fields.push_back({"traction", Eigen::MatrixXd::Zero(wall.mesh.num_points(), 3)});
  return wall;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_sample_output CASE.toml OUTDIR\n");
    return 2;
  }
  Case c = read_case(argv[1]);
  c.output.dir = argv[2];
  prepare_output_dir(c.output.dir);
  write_case_toml(c, c.output.dir / "case.toml");
  const int order = c.cells->order;
  const SHTransform t = SHTransform::gauss(order);
  const std::vector<SHSurface> cells = placed_cells(*c.cells, order);
  const Vec3 u = c.domain.mean_velocity.value_or(Vec3{0, 0, 0});

  XdmfWriter xdmf(c.output.dir);
  VtkSeriesWriter vtk(c.output.dir);
  DiagnosticsCsv diagnostics(c.output.dir / "diagnostics.csv");
  CellsCsv cells_csv(c.output.dir / "cells.csv");
  for (int frame = 0; frame < 3; ++frame) {
    const long step = 10L * frame;
    const double time = step * time_step(c);
    std::vector<Surface> parts;
    std::vector<CellRow> rows;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      SHSurface s = cells[k];
      s.translate(Eigen::Vector3d(u[0], u[1], u[2]) * time);
      const SurfaceGeometry g = s.geometry(t);
      Surface part{"cell", s.triangulate(t), {}};
      const int n = part.mesh.num_points();
      Eigen::MatrixXd curvature(n, 1);
      curvature.topRows(g.size()) = g.mean_curvature;
      curvature.bottomRows(2) << g.mean_curvature(0), g.mean_curvature(g.size() - 1);  // poles: nearest ring
      part.fields = {{"velocity", Eigen::RowVector3d(u[0], u[1], u[2]).replicate(n, 1)},
                     {"force", Eigen::MatrixXd::Zero(n, 3)},
                     {"tension", Eigen::MatrixXd::Zero(n, 1)},
                     {"J_S", Eigen::MatrixXd::Ones(n, 1)},
                     {"mean_curvature", curvature}};
      parts.push_back(std::move(part));
      const Eigen::Vector3d centre = volume_centroid(g);
      rows.push_back({step, time, static_cast<int>(k), {centre.x(), centre.y(), centre.z()}, u,
                      enclosed_volume(g), surface_area(g), 0.0, 0.0});
    }
    std::vector<Surface> surfaces = {merge_surfaces("cells", parts)};
    if (c.vessel && c.vessel->kind == VesselKind::tube) surfaces.push_back(tube_wall(c));
    if (c.output.xdmf) xdmf.write_frame(step, time, surfaces);
    if (c.output.vtk) vtk.write_frame(step, time, surfaces);
    cells_csv.write(rows);
    for (long s = step; s < step + 10; ++s) {
      DiagnosticsRow r;
      r.step = s;
      r.time = s * time_step(c);
      r.dt = time_step(c);
      r.mean_velocity = u;
      r.pressure_gradient = {0, 0, -2.0 - std::exp(-0.1 * s)};
      if (c.vessel) r.effective_viscosity = 1.5 + 0.5 * std::exp(-0.1 * s);
      diagnostics.write(r);
    }
  }
  std::printf("sample output in %s\n", c.output.dir.c_str());
  return 0;
}
