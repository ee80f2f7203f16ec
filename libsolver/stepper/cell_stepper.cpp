#include "cell_stepper.h"

#include <cmath>
#include <stdexcept>

namespace rbcflow {

CellStepper::CellStepper(std::vector<Cell> cells, std::shared_ptr<const CellGrids> grids, CellStepperOptions options)
    : cells_(std::move(cells)), grids_(std::move(grids)), options_(std::move(options)) {
  if (cells_.empty()) throw std::invalid_argument("CellStepper: no cells");
  if (!(options_.dt > 0)) throw std::invalid_argument("CellStepper: dt must be positive");
  if (!options_.domain.box && !options_.background) {
    options_.background = [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero().eval(); };
  }
  for (const Cell& c : cells_) {
    const SurfaceGeometry g = c.shape.geometry(*grids_->n_grid);
    volume0_.push_back(enclosed_volume(g));
    area0_.push_back(surface_area(g));
  }
}

void CellStepper::enforce_volume(int c) {
  // Move the surface along its normal by the uniform delta = (V0 - V) / A (twice: the
  // correction is first order), the variational volume constraint of section 10.2.
  for (int it = 0; it < 2; ++it) {
    const SurfaceGeometry g = cells_[c].shape.geometry(*grids_->n_grid);
    const double delta = (volume0_[c] - enclosed_volume(g)) / surface_area(g);
    const Eigen::MatrixXd shift = delta * g.normal;
    cells_[c].shape.coeffs().values() += grids_->n_grid->analyze(shift).values();
  }
}

StepReport CellStepper::step() {
  const int nc = static_cast<int>(cells_.size());
  const int np = grids_->n_grid->grid().size();
  const SHTransform& tn = *grids_->n_grid;

  // Hydrodynamic traction: the membrane's (eq. 23) minus the body-force density.
  std::vector<SHCoeffs> shapes(nc);
  Eigen::MatrixXd traction(nc * np, 3);
#pragma omp parallel for schedule(dynamic)
  for (int c = 0; c < nc; ++c) {
    shapes[c] = cells_[c].shape.coeffs();
    const MembraneState m = cells_[c].membrane->compute(shapes[c]);
    traction.middleRows(c * np, np) = m.traction_grid;
  }
  CellLayers layers(shapes, grids_, options_.domain, options_.quadrature, options_.viscosity_ratio != 1.0);
  for (int c = 0; c < nc; ++c) {
    if (cells_[c].body_force.isZero()) continue;
    const double area = layers.cell(c).nodes().weight.sum();
    traction.middleRows(c * np, np).rowwise() -= (cells_[c].body_force / area).transpose();
  }
  Eigen::MatrixXd background(nc * np, 3);
  for (int r = 0; r < nc * np; ++r) {
    background.row(r) = options_.domain.box ? options_.mean_velocity
                                            : options_.background(Eigen::Vector3d(layers.nodes().x.row(r)));
  }
  const VelocitySolve v = solve_cell_velocity(layers, traction, options_.viscosity_ratio, background,
                                              options_.gmres_tolerance, options_.gmres_max_iterations, velocity_);
  if (!v.gmres.converged) {
    throw std::runtime_error("GMRES for the cell velocity did not converge at step " + std::to_string(steps_ + 1) +
                             ": relative residual " + std::to_string(v.gmres.relative_residual) + " after " +
                             std::to_string(v.gmres.iterations) + " iterations");
  }
  velocity_ = v.velocity;

  // X^{n+1} = X^n + dt U^n (eq. 11), or AB2 with the previous rate.
  const bool ab2 = options_.scheme == TimeScheme::ab2 && !previous_rate_.empty();
  std::vector<SHCoeffs> rate(nc);
  StepReport report;
  report.gmres_iterations = v.gmres.iterations;
  report.gmres_residual = v.gmres.relative_residual;
  for (int c = 0; c < nc; ++c) {
    rate[c] = tn.analyze(velocity_.middleRows(c * np, np));
    Eigen::MatrixXd& x = cells_[c].shape.coeffs().values();
    if (ab2) {
      x += options_.dt * (1.5 * rate[c].values() - 0.5 * previous_rate_[c].values());
    } else {
      x += options_.dt * rate[c].values();
    }
    if (options_.volume_constraint) enforce_volume(c);
    const SurfaceGeometry g = cells_[c].shape.geometry(tn);
    const double dv = std::abs(enclosed_volume(g) / volume0_[c] - 1.0), da = std::abs(surface_area(g) / area0_[c] - 1.0);
    if (!std::isfinite(dv) || !std::isfinite(da)) {
      throw std::runtime_error("cell " + std::to_string(c) + " became invalid (NaN) at step " + std::to_string(steps_ + 1));
    }
    report.max_volume_error = std::max(report.max_volume_error, dv);
    report.max_area_error = std::max(report.max_area_error, da);
  }
  previous_rate_ = std::move(rate);
  time_ += options_.dt;
  ++steps_;
  return report;
}

}  // namespace rbcflow
