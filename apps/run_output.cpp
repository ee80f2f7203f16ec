#include "run_output.h"

#include <cmath>
#include <numbers>

#include "geometry/inertia_ellipsoid.h"
#include "geometry/vessel_mesh.h"
#include "io/xdmf_writer.h"

namespace rbcflow::cli {

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

std::vector<Surface> frame_surfaces(const CellStepper& stepper, const FlowSolution& s) {
  std::vector<Surface> surfaces;
  const auto& cells = stepper.cells();
  if (!cells.empty()) {
    const SHTransform& t = *stepper.grids().n_grid;
    const int np = t.grid().size();
    std::vector<Surface> parts;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const MembraneState& m = s.membrane[c];
      Surface part{"cell", cells[c].shape.triangulate(t), {}};
      const Eigen::MatrixXd tension = 0.5 * m.principal_tension.rowwise().sum();
      part.fields = {{"velocity", with_poles(s.velocity.middleRows(c * np, np), t.grid())},
                     {"force", with_poles(s.traction.middleRows(c * np, np), t.grid())},
                     {"tension", with_poles(tension, t.grid())},
                     {"max_tension", with_poles(m.principal_tension.col(0), t.grid())},
                     {"J_S", with_poles(m.dilatation, t.grid())}};
      parts.push_back(std::move(part));
    }
    surfaces.push_back(merge_surfaces("cells", parts));
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
  if (stepper.cells().empty()) return rows;
  const SHTransform& t = *stepper.grids().n_grid;
  const int np = t.grid().size();
  for (std::size_t c = 0; c < stepper.cells().size(); ++c) {
    const SurfaceGeometry g = stepper.cells()[c].shape.geometry(t);
    const Eigen::Vector3d centre = volume_centroid(g);
    const Eigen::Vector3d u =
        (s.velocity.middleRows(c * np, np).transpose() * g.area_weight) / g.area_weight.sum();
    const InertiaEllipsoid e = inertia_ellipsoid(g);
    const Eigen::Vector3d longest = e.axes.col(2);
    double inclination = 0;
    if (shear) {
      inclination = std::atan2(longest.z(), longest.x());
      if (inclination > std::numbers::pi / 2) inclination -= std::numbers::pi;
      if (inclination <= -std::numbers::pi / 2) inclination += std::numbers::pi;
    } else {
      inclination = std::acos(std::min(1.0, std::abs(longest[flow_axis])));
    }
    rows.push_back({stepper.steps(), stepper.time(), static_cast<int>(c), {centre.x(), centre.y(), centre.z()},
                    {u.x(), u.y(), u.z()}, enclosed_volume(g), surface_area(g), e.taylor_deformation(), inclination});
  }
  return rows;
}

void write_checkpoint(const CellStepper& stepper, const Case& c, const std::filesystem::path& file) {
  const StepperState state = stepper.state();
  CheckpointWriter w(case_fingerprint(c));
  w.put("time", state.time);
  w.put("steps", static_cast<long long>(state.steps));
  w.put("cells/count", static_cast<long long>(state.shapes.size()));
  for (std::size_t k = 0; k < state.shapes.size(); ++k) {
    const std::string cell = "cells/" + std::to_string(k) + "/";
    w.put(cell + "coefficients", state.shapes[k].values());
    w.put(cell + "reference", stepper.cells()[k].membrane->reference().coeffs().values());
  }
  w.put("cells/initial_volume", Eigen::Map<const Eigen::VectorXd>(state.volume0.data(), state.volume0.size()));
  w.put("cells/initial_area", Eigen::Map<const Eigen::VectorXd>(state.area0.data(), state.area0.size()));
  // The multistep history and the staggered coupling, U^{n-1} and F^{n-1}; the GMRES guesses'
  // U^{n-2}, U^{n-3} and F^{n-2}.
  if (state.previous_velocity.size()) w.put("cells/previous_velocity", state.previous_velocity);
  if (state.older_velocity.size()) w.put("cells/older_velocity", state.older_velocity);
  if (state.oldest_velocity.size()) w.put("cells/oldest_velocity", state.oldest_velocity);
  if (state.previous_wall_force.size()) w.put("wall/previous_force", Eigen::MatrixXd(state.previous_wall_force));
  if (state.older_wall_force.size()) w.put("wall/older_force", Eigen::MatrixXd(state.older_wall_force));
  if (const WallCoupling* wall = stepper.wall()) {
    w.put("wall/points", wall->elements().wall.surface.points);
    w.put("wall/triangles", wall->elements().wall.surface.triangles);
  }
  w.write(file);
}

void read_checkpoint(CellStepper& stepper, const Case& c, const std::filesystem::path& file) {
  const Checkpoint k = Checkpoint::read(file, case_fingerprint(c));
  auto fail = [&](const std::string& why) { throw CheckpointError(file.string() + ": " + why); };
  const std::size_t n = stepper.cells().size();
  if (k.integer("cells/count") != static_cast<long long>(n))
    fail("it holds " + std::to_string(k.integer("cells/count")) + " cells, the case " + std::to_string(n));
  StepperState s;
  s.time = k.real("time");
  s.steps = k.integer("steps");
  const int order = n ? stepper.cells()[0].shape.coeffs().order() : 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::MatrixXd& v = k.matrix("cells/" + std::to_string(i) + "/coefficients");
    SHCoeffs x(order, 3);
    if (v.rows() != x.values().rows() || v.cols() != 3) fail("cell " + std::to_string(i) + " has another order");
    x.values() = v;
    s.shapes.push_back(std::move(x));
  }
  if (n) {
    const Eigen::MatrixXd& v0 = k.matrix("cells/initial_volume");
    const Eigen::MatrixXd& a0 = k.matrix("cells/initial_area");
    s.volume0.assign(v0.data(), v0.data() + v0.size());
    s.area0.assign(a0.data(), a0.data() + a0.size());
    if (k.has("cells/previous_velocity")) s.previous_velocity = k.matrix("cells/previous_velocity");
    if (k.has("cells/older_velocity")) s.older_velocity = k.matrix("cells/older_velocity");
    if (k.has("cells/oldest_velocity")) s.oldest_velocity = k.matrix("cells/oldest_velocity");
  }
  if (const WallCoupling* wall = stepper.wall()) {
    if (!k.has("wall/points") || k.matrix("wall/points").rows() != wall->elements().num_nodes())
      fail("its wall does not match the case's vessel as meshed now");
    if (k.has("wall/previous_force")) s.previous_wall_force = k.matrix("wall/previous_force");
    if (k.has("wall/older_force")) s.older_wall_force = k.matrix("wall/older_force");
  }
  try {
    stepper.restore(s);
  } catch (const std::invalid_argument& e) {
    fail(e.what());
  }
}

std::filesystem::path checkpoint_path(const std::filesystem::path& dir, long step) {
  return dir / "checkpoints" / ("step_" + step_label(step) + ".h5");
}

std::filesystem::path render_path(const std::filesystem::path& dir, long step) {
  return dir / "renders" / ("step_" + step_label(step) + ".png");
}

}  // namespace rbcflow::cli
