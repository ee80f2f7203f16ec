#include "scenario/run_output.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "geometry/vessel/vessel_mesh.h"
#include "io/xdmf_writer.h"
#include "libsolver/stepper/cell_measures.h"
#include "libsolver/wall/tube_flow.h"
#include "scenario/derived.h"
#include "scenario/physical_units.h"

namespace rbcflow {

namespace {

// A grid field with the two pole points that triangulate() appends: the mean of the nearest
// ring of the grid (first and last rows of a Gauss grid).
Eigen::MatrixXd with_poles(const Eigen::MatrixXd& grid_values, const SphGrid& grid) {
  const int n = static_cast<int>(grid_values.rows()), ring = grid.n_phi();
  Eigen::MatrixXd out(n + 2, grid_values.cols());
  out.topRows(n) = grid_values;
  out.row(n) = grid_values.topRows(ring).colwise().mean();
  out.row(n + 1) = grid_values.bottomRows(ring).colwise().mean();
  return out;
}

}  // namespace

long cell_frame_points(const CellStepper& stepper) {
  return stepper.cells().empty() ? 0 : stepper.grids().n_grid->grid().size() + 2;
}

long cell_frame_triangles(const CellStepper& stepper) {
  return stepper.cells().empty() ? 0 : 2 * stepper.grids().n_grid->grid().size();  // SHSurface::triangulate's
}

std::vector<Surface> frame_surfaces(const CellStepper& stepper, const FlowSolution& s, const CellsForOutput& cells,
                                    int begin, int end) {
  std::vector<Surface> surfaces;
  if (!stepper.cells().empty()) {
    const SHTransform& t = *stepper.grids().n_grid;
    const int np = t.grid().size();
    const auto first = std::lower_bound(cells.cells.begin(), cells.cells.end(), begin) - cells.cells.begin();
    if (end < begin || first + (end - begin) > static_cast<long>(cells.cells.size()) ||
        (end > begin && cells.cells[static_cast<std::size_t>(first + (end - begin) - 1)] != end - 1))
      throw std::invalid_argument("frame_surfaces: the cells " + std::to_string(begin) + ".." + std::to_string(end - 1) +
                                  " are not all brought for output");
    std::vector<Surface> parts;
    for (long i = first; i < first + (end - begin); ++i) {
      const MembraneState& m = cells.membranes[static_cast<std::size_t>(i)];
      Surface part{"cell", cells.shapes[static_cast<std::size_t>(i)].triangulate(t), {}};
      const Eigen::MatrixXd tension = 0.5 * m.principal_tension.rowwise().sum();
      part.fields = {{"velocity", with_poles(cells.velocity.middleRows(i * np, np), t.grid())},
                     {"force", with_poles(cells.traction.middleRows(i * np, np), t.grid())},
                     {"tension", with_poles(tension, t.grid())},
                     {"max_tension", with_poles(m.principal_tension.col(0), t.grid())},
                     {"J_S", with_poles(m.dilatation, t.grid())}};
      parts.push_back(std::move(part));
    }
    // A rank with no cell to write writes none of the surface, with its fields all the same.
    if (parts.empty()) parts.push_back(Surface{"cell", TriangleMesh{Eigen::MatrixX3d(0, 3), Eigen::MatrixX3i(0, 3)},
                                               {{"velocity", Eigen::MatrixXd(0, 3)}, {"force", Eigen::MatrixXd(0, 3)},
                                                {"tension", Eigen::MatrixXd(0, 1)}, {"max_tension", Eigen::MatrixXd(0, 1)},
                                                {"J_S", Eigen::MatrixXd(0, 1)}}});
    Surface merged = merge_surfaces("cells", parts);
    // Numbered as in the whole frame: the cells before `begin` come first.
    merged.mesh.triangles.array() += static_cast<int>(begin * cell_frame_points(stepper));
    for (SurfaceField& f : merged.fields)
      if (f.name == "cell") f.values.array() += begin;
    surfaces.push_back(std::move(merged));
  }
  if (const WallCoupling* wall = stepper.wall()) {
    // Drawn without triangles across the box: nodes on the far side of a face are copies,
    // whose traction is their original node's.
    const TriangleMesh& mesh = wall->elements().wall.surface;
    Surface w{"wall", drawable_surface(wall->elements().wall), {}};
    Eigen::MatrixXd traction(w.mesh.num_points(), 3);
    traction.topRows(mesh.num_points()) = s.wall_force;
    for (int t = 0; t < mesh.num_triangles(); ++t)
      for (int a = 0; a < 3; ++a) traction.row(w.mesh.triangles(t, a)) = s.wall_force.row(mesh.triangles(t, a));
    w.fields = {{"traction", traction}};
    surfaces.push_back(std::move(w));
  }
  return surfaces;
}

std::vector<CellRow> cell_rows(const CellStepper& stepper, const FlowSolution& s, int flow_axis, bool shear) {
  std::vector<CellRow> rows;
  const std::vector<CellMeasures> measures = stepper.cell_measures(s);
  for (std::size_t c = 0; c < measures.size(); ++c) {
    const CellMeasures& m = measures[c];
    const Eigen::Vector3d& longest = m.longest_axis;
    double inclination = 0;
    if (shear) {
      inclination = std::atan2(longest.z(), longest.x());
      if (inclination > std::numbers::pi / 2) inclination -= std::numbers::pi;
      if (inclination <= -std::numbers::pi / 2) inclination += std::numbers::pi;
    } else {
      inclination = std::acos(std::min(1.0, std::abs(longest[flow_axis])));
    }
    rows.push_back({stepper.steps(), stepper.time(), static_cast<int>(c),
                    {m.centroid.x(), m.centroid.y(), m.centroid.z()}, {m.velocity.x(), m.velocity.y(), m.velocity.z()},
                    m.volume, m.area, m.taylor_deformation, inclination});
  }
  return rows;
}

RenderOptions render_options(const Case& c) {
  RenderOptions o;
  o.field = c.cells ? c.output.render_field : "none";
  o.view = c.output.render_view;
  o.width = c.output.render_size[0];
  o.height = c.output.render_size[1];
  o.axis = flow_axis(c);
  o.period = flow_period(c);
  return o;
}

DiagnosticsRow diagnostics_row(const CellStepper& stepper, const StepReport& r, const Scenario& s, double seconds) {
  const Case& c = s.c;
  DiagnosticsRow row;
  row.step = stepper.steps();
  row.time = stepper.time();
  row.dt = stepper.dt();
  row.mean_velocity = {r.mean_velocity.x(), r.mean_velocity.y(), r.mean_velocity.z()};
  row.pressure_gradient = {r.pressure_gradient.x(), r.pressure_gradient.y(), r.pressure_gradient.z()};
  if (s.tube_radius) {
    const int a = c.vessel->axis;
    const double side = c.domain.box[(a + 1) % 3];
    if (side == c.domain.box[(a + 2) % 3]) {  // (45) is for a square cross-section
      row.effective_viscosity =
          tube_effective_viscosity(*s.tube_radius, side, r.mean_velocity[a], r.pressure_gradient[a]);
    }
  }
  if (!stepper.cells().empty()) row.tube_hematocrit = s.tube_hematocrit;
  if (r.tube_velocity) {
    row.tube_velocity = r.tube_velocity;
    row.pseudo_shear_rate_per_s = PhysicalUnits(c.units).per_second(*r.tube_velocity / c.vessel->diameter);
  }
  row.discharge_hematocrit = r.discharge_hematocrit;
  if (!stepper.cells().empty()) {
    row.max_area_strain = r.max_area_strain;
    row.max_area_strain_cell = r.max_area_strain_cell;
  }
  row.cell_free_layer = r.cell_free_layer;
  row.min_wall_gap = r.min_wall_gap;
  row.max_volume_correction = r.max_volume_correction;
  row.max_volume_error = r.max_volume_error;
  row.max_area_error = r.max_area_error;
  row.gmres_cells = r.gmres_iterations;
  if (stepper.wall()) {
    row.gmres_wall = r.gmres_wall;
    row.wall_residual = r.wall_residual;
  }
  row.seconds = seconds;
  if (c.time.collision_threshold > 0 && !stepper.cells().empty()) {
    row.collision_pairs = r.collision_pairs;
    row.wall_contacts = r.wall_contacts;
    row.collision_displacement = r.collision_displacement;
  }
  if (r.contact) {
    row.max_contact_traction = r.contact->max_traction;
    row.contact_cells = r.contact->cells_in_range;
  }
  return row;
}

std::filesystem::path checkpoint_path(const std::filesystem::path& dir, long step) {
  return dir / "checkpoints" / ("step_" + step_label(step) + ".h5");
}

std::filesystem::path render_path(const std::filesystem::path& dir, long step) {
  return dir / "renders" / ("step_" + step_label(step) + ".png");
}

}  // namespace rbcflow
