#include "cell_stepper.h"
#include "step_memory.h"

#include <algorithm>
#include <array>
#include <set>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <stdexcept>
#include <string>

#include "libsolver/linear/anderson_mixing.h"
#include "libsolver/operators/cell_layers_at_points.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/owned_rows.h"
#include "libsolver/stepper/cell_centroids.h"
#include "libsolver/stepper/cell_measures.h"
#include "libsolver/stepper/cell_flux.h"
#include "libsolver/stepper/cell_free_layer.h"
#include "libsolver/stepper/halo_density.h"
#include "libsolver/stepper/held_shapes.h"
#include "libsolver/stepper/step_slabs.h"

namespace rbcflow {

namespace {

// Pointers to the cells' shapes, by cell number (held_shapes.h).
std::vector<SHCoeffs*> shapes_of(std::vector<Cell>& cells) {
  std::vector<SHCoeffs*> x;
  for (Cell& c : cells) x.push_back(&c.shape.coeffs());
  return x;
}

// The rows (nodes_per_cell a cell) of the cells `owners` gives rank `rank` in `held`, a matrix
// whose rows are stacked in `held_by`'s order (zero where not read), in `owners`' order.
// `held_positions` (ascending positions in held_by's order): `held` stacks only those cells'
// rows (OwnedRows' held layout); empty: every cell's.
Eigen::MatrixXd rows_of_owned(const Eigen::MatrixXd& held, const CellOwners& held_by, const CellOwners& owners,
                              int rank, int np, const std::vector<int>& held_positions = {}) {
  std::vector<int> position(held_by.order.size());
  for (std::size_t k = 0; k < held_by.order.size(); ++k) position[static_cast<std::size_t>(held_by.order[k])] = static_cast<int>(k);
  auto row = [&](int c) -> Eigen::Index {
    const int p = position[static_cast<std::size_t>(c)];
    if (held_positions.empty()) return static_cast<Eigen::Index>(p) * np;
    return (std::lower_bound(held_positions.begin(), held_positions.end(), p) - held_positions.begin()) * np;
  };
  const int first = owners.first[rank], end = owners.first[rank + 1];
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(end - first) * np, 3);
  for (int k = first; k < end; ++k)
    rows.middleRows(static_cast<Eigen::Index>(k - first) * np, np) = held.middleRows(row(owners.order[k]), np);
  return rows;
}

// The largest of the ranks' values, the same on every rank.
double largest(double value, const Communicator& ranks) { return -ranks.min(-value); }

constexpr double kPi = std::numbers::pi;
constexpr int kMaxStartSweeps = 20;
constexpr double kStartSweepTolerance = 1e-5;
constexpr int kStartSweepDepth = 5;
constexpr double kStartSweepForcing = 0.01;

std::string at_step(long step) { return " at step " + std::to_string(step); }

// Stops a pool keeping its arrays, and frees them, when it goes.
struct KeptUntilReturn {
  WorkArrayPool& pool;
  ~KeptUntilReturn() { pool.keep(false); }
};

}  // namespace

CellStepper::CellStepper(std::vector<Cell> cells, std::shared_ptr<const CellGrids> grids, CellStepperOptions options)
    : cells_(std::move(cells)), grids_(std::move(grids)), options_(std::move(options)) {
  if (cells_.empty() && !options_.wall) throw std::invalid_argument("CellStepper: no cells and no wall");
  if (!cells_.empty() && !grids_) throw std::invalid_argument("CellStepper: cells need their grids");
  if (!(options_.dt > 0)) throw std::invalid_argument("CellStepper: dt must be positive");
  if (!(options_.viscosity_ratio > 0)) throw std::invalid_argument("CellStepper: the viscosity ratio must be positive");
  if (!(options_.contact.range >= 0) || !(options_.contact.strength >= 0) ||
      (options_.contact.range > 0 && options_.contact.strength == 0))
    throw std::invalid_argument("CellStepper: a contact repulsion needs a positive range and strength");
  if (!options_.domain.box && !options_.background) {
    options_.background = [](const Eigen::Vector3d&) { return Eigen::Vector3d::Zero().eval(); };
  }
  if (options_.wall) {
    if (!options_.domain.box) throw std::invalid_argument("CellStepper: a vessel wall needs a periodic box");
    options_.wall_solve.ranks = options_.domain.ranks;  // the wall's rows shared by the cells' ranks
    wall_ = std::make_unique<WallCoupling>(options_.wall, *options_.domain.box, options_.domain.ewald_tolerance,
                                           options_.wall_solve, work_arrays_);
    if (options_.collision_threshold > 0 || !cells_.empty())  // collisions; the cells' gap to the wall
      wall_distance_ = std::make_unique<WallDistance>(options_.wall->wall);
    if (options_.tube_velocity && !options_.tube) {
      throw std::invalid_argument("CellStepper: a tube velocity needs the tube's section");
    }
    if (options_.tube_velocity && options_.pressure_gradient) {
      throw std::invalid_argument("CellStepper: give a tube velocity or a pressure gradient, not both");
    }
    if (options_.tube) {
      tube_meter_.emplace(*wall_, *options_.tube);
      if (options_.tube_velocity) {
        options_.mean_velocity = Eigen::Vector3d::Unit(options_.tube->axis) * (*options_.tube_velocity / tube_meter_->ratio());
      }
    }
    if (!options_.flux_sections.empty())
      section_meter_ = std::make_unique<SectionFluxMeter>(*wall_, std::move(options_.flux_sections));
  } else if (!options_.flux_sections.empty()) {
    throw std::invalid_argument("CellStepper: flux sections need a vessel wall");
  } else if (options_.pressure_gradient) {
    throw std::invalid_argument("CellStepper: a prescribed pressure gradient needs a vessel wall to resist it");
  } else if (options_.tube || options_.tube_velocity) {
    throw std::invalid_argument("CellStepper: a tube velocity needs a vessel wall");
  }
  for (const Cell& c : cells_) {
    const SurfaceGeometry g = c.shape.geometry(*grids_->n_grid);
    state_.volume0.push_back(enclosed_volume(g));
    state_.area0.push_back(surface_area(g));
  }
  history_owners_ = owners_by_block(static_cast<int>(cells_.size()), options_.domain.ranks.size());
}

namespace {

// The GMRES initial guess: the polynomial through the last solutions x^{n-1}, x^{n-2}, x^{n-3}
// (newest first), evaluated one step on: x^{n-1} (k = 1 of them), 2 x^{n-1} - x^{n-2} (k = 2),
// 3 x^{n-1} - 3 x^{n-2} + x^{n-3} (k = 3), O(dt^k) from the solution of a smooth history. The
// history ends at the first empty or mismatched entry (the first steps, a restored state).
// The cells' velocity is smooth at the step's scale (tube27: |second difference| / |first| =
// 0.06), and its quadratic guess takes 3-4 iterations where the linear took 6 (a cubic took
// 4). The wall force is not (that ratio is 0.3-1.6 from step to step in tube27 and the
// minicase): it keeps the linear guess, with which the minicase's wall solve takes 1.9
// iterations per step against 2.6 from the quadratic (docs/performance.md, "Tried and left out").
template <typename Matrix>
Matrix extrapolated(std::initializer_list<const Matrix*> history) {
  std::array<const Matrix*, 3> x{};
  int k = 0;
  for (const Matrix* m : history) {
    if (k == 3 || m->size() == 0 || m->rows() != (*history.begin())->rows()) break;
    x[k++] = m;
  }
  switch (k) {
    case 0: return Matrix();
    case 1: return *x[0];
    case 2: return 2 * *x[0] - *x[1];
    default: return 3 * (*x[0] - *x[1]) + *x[2];
  }
}

}  // namespace

FlowSolution CellStepper::solve() const {
  const PointField force_guess = extrapolated<PointField>({&state_.previous_wall_force, &state_.older_wall_force});
  const int nc = static_cast<int>(cells_.size());
  const int np = points_per_cell();
  const double lambda = options_.viscosity_ratio;
  const long step = state_.steps + 1;
  FlowSolution s;
  StepTimings& timing = s.timings;
  ScopedTimer total_timer(timing.total);
  s.mean_velocity = options_.mean_velocity;

  // The products' largest grid array is kept from the first solve of (10) on, once every
  // operator of the step is built (the wall's at the cell nodes takes a gigabyte while built at
  // a thousand cells), and freed as solve() returns or throws.
  const KeptUntilReturn kept_work_arrays(*work_arrays_);
  release_heap_memory();  // what the last step freed into the heaps (step_memory.h)
  // Hydrodynamic traction: the membrane's (eq. 23) minus the body-force density.
  std::unique_ptr<CellLayers> layers;
  // The layer products take the cells in their owners' order (cell_owners.h; the cells' own on
  // one rank): the node data of the products below are in that order; s.velocity holds this
  // rank's owned cells' rows until the end.
  CellOwners owners = owners_by_block(nc, options_.domain.ranks.size());
  std::optional<HaloDensity> step_traction;
  std::vector<SlabPlanes> other_slabs;  // this rank's of the grids of the step's other operators
  std::vector<int> step_halo;           // the cells this rank reads or adds to besides its own (positions in owner order)
  std::vector<int> held_cells;          // the owned and step_halo, ascending (one process: every cell; a rank may hold none)
  std::vector<SHCoeffs> shapes;         // in owner order: the held cells' (several ranks; one: every cell)
  std::vector<CellSphere> owner_spheres;  // the cells' spheres in owner order (several ranks)
  const Eigen::MatrixXd* traction = nullptr;  // step_traction's density, which the operators read
  Eigen::Vector3d external_force = Eigen::Vector3d::Zero();  // on the cells: body forces and the repulsion's
  DensityHalo bring_traction;                 // the rows of it an operator reads, brought
  if (nc > 0) {
    // The owners from the cells' spheres, each computed by the rank that moved the cell last
    // (history_owners_) and gathered; one process owns every cell and needs none.
    std::vector<CellSphere> spheres(nc);
    if (options_.domain.ranks.size() > 1) {
      const int held_first = history_owners_.first[options_.domain.ranks.rank()];
      const int held_end = history_owners_.first[options_.domain.ranks.rank() + 1];
#pragma omp parallel for schedule(dynamic)
      for (int k = held_first; k < held_end; ++k) {
        const int c = history_owners_.order[k];
        spheres[c] = cell_sphere(cells_[c].shape.coeffs(), *grids_);
      }
      share_spheres(spheres, history_owners_, options_.domain.ranks);
    }
    owners = cell_owners(spheres, np, options_.domain, lambda != 1.0, grid_cache_.get());
    // This rank's slabs of the other operators' grids, before any is built: with the layers'
    // own, the step's halo (step_slabs.h).
    const std::optional<long> section_points =
        section_meter_ ? section_meter_->points_per_step() : std::optional<long>{};
    other_slabs = step_slabs(options_.domain,
                             StepOperators{static_cast<long>(nc) * np, lambda != 1.0, wall_.get(),
                                           static_cast<bool>(section_meter_), section_points},
                             grid_cache_.get());
    if (options_.domain.ranks.size() > 1) {
      owner_spheres.resize(nc);
      for (int k = 0; k < nc; ++k) owner_spheres[k] = spheres[owners.order[k]];
      LayerDomain owned_domain = options_.domain;
      owned_domain.owned_first = owners.first;
      step_halo = cell_layers_halo(owner_spheres, *grids_, owned_domain, options_.quadrature, lambda != 1.0,
                                   grid_cache_.get(), other_slabs);
    }
    // The shapes in owner order: each rank holds its own in history_owners_ (held_shapes.h) and
    // brings those of the cells it holds besides in the products (its own and the step's halo).
    const int r = options_.domain.ranks.rank();
    const int first = owners.first[r], end = owners.first[r + 1];
    shapes.resize(nc);
    if (options_.domain.ranks.size() > 1) {
      for (int k = first; k < end; ++k) held_cells.push_back(k);
      held_cells.insert(held_cells.end(), step_halo.begin(), step_halo.end());
      std::sort(held_cells.begin(), held_cells.end());
      std::vector<SHCoeffs*> by_cell(nc);
      std::vector<int> bring;
      for (int k = 0; k < nc; ++k) {
        const SHCoeffs& x = cells_[owners.order[k]].shape.coeffs();
        shapes[k] = shape_held(x) ? x : shape_not_held(x.order());
        by_cell[owners.order[k]] = &shapes[k];
      }
      for (int k : held_cells) bring.push_back(owners.order[k]);
      s.shapes_received = bring_shapes(by_cell, history_owners_, bring, options_.domain.ranks);
    } else {
      for (int k = 0; k < nc; ++k) {
        shapes[k] = cells_[owners.order[k]].shape.coeffs();
        held_cells.push_back(k);
      }
    }
    s.membrane.resize(nc);
    ScopedTimer membrane_timer(timing.membrane);
    // Each rank the membranes of the cells it owns in the products; the operators bring the
    // rows of the others' tractions they read (halo_density.h), the output the rest of their
    // states (cells_for_output).
    Eigen::MatrixXd owned(static_cast<Eigen::Index>(end - first) * np, 3);
#pragma omp parallel for schedule(dynamic)
    for (int k = first; k < end; ++k) {
      const int c = owners.order[k];
      s.membrane[c] = cells_[c].membrane->compute(shapes[k]);
      auto rows = owned.middleRows(static_cast<Eigen::Index>(k - first) * np, np);
      rows = s.membrane[c].traction_grid;
      if (cells_[c].body_force.isZero()) continue;
      const double area = surface_area(SHSurface(shapes[k]).geometry(*grids_->n_grid));
      rows.rowwise() -= (cells_[c].body_force / area).transpose();
    }
    if (options_.contact.active()) {
      // The repulsion on this rank's own cells from every surface within its range: the
      // cells near them are in the step's halo (held), which reaches the near-field distance.
      std::vector<int> own(static_cast<std::size_t>(end - first));
      for (int k = first; k < end; ++k) own[k - first] = k;
      if (options_.domain.ranks.size() > 1)
        for (int k = first; k < end; ++k)
          if (options_.contact.range > cell_near_reach(owner_spheres[k].area, grids_->order, options_.quadrature))
            throw std::invalid_argument("the contact range " + std::to_string(options_.contact.range) +
                                        " exceeds the cells' near-field reach, which bounds the cells a rank holds");
      const Eigen::Vector3d period = options_.domain.box ? options_.domain.box->lengths() : Eigen::Vector3d::Zero();
      ContactReport near;
      const Eigen::MatrixXd g = contact_force_density(shapes, own, *grids_->n_grid, period, wall_distance_.get(), options_.contact, near);
      owned -= g;
      for (int k = first; k < end; ++k) {  // the repulsion's net force on each cell
        const SurfaceGeometry geometry = SHSurface(shapes[k]).geometry(*grids_->n_grid);
        external_force += g.middleRows(static_cast<Eigen::Index>(k - first) * np, np).transpose() * geometry.area_weight;
      }
      const Communicator& ranks = options_.domain.ranks;
      near.cells_near_cells = static_cast<int>(ranks.sum(static_cast<long>(near.cells_near_cells)));
      near.cells_near_wall = static_cast<int>(ranks.sum(static_cast<long>(near.cells_near_wall)));
      near.cells_in_range = static_cast<int>(ranks.sum(static_cast<long>(near.cells_in_range)));
      near.max_traction = -ranks.min(-near.max_traction);
      near.min_separation = ranks.min(near.min_separation);
      s.contact = near;
    }
    // The cells' external loads, body forces and the repulsion's, exert a net force on the fluid
    // (the membrane's own traction integrates to zero on a closed surface): the periodic sums
    // balance it by a uniform force density, a part of the mean pressure gradient (8) that the
    // paper's force-free cells never carry (<grad p> = -(F_wall - external) / V).
    for (int k = first; k < end; ++k) external_force += cells_[owners.order[k]].body_force;
    options_.domain.ranks.sum(external_force);  // exactly zero without loads: (8) as the paper's
    membrane_timer.stop();
    LayerDomain domain = options_.domain;
    domain.owned_first = owners.first;
    // The layers hold the nodes of the step's halo besides their own, not every cell's.
    if (options_.domain.ranks.size() > 1) domain.held = HeldCells{step_halo, std::move(owner_spheres)};
    // The densities at the layers' held rows (cell_layers.h): no matrix of every cell's rows.
    step_traction.emplace(std::move(owned), owners, np, options_.domain.ranks, held_cells);
    traction = &step_traction->density();
    bring_traction = step_traction->bringer();
    // The traction is the step's only single-layer density: its single layer is computed as
    // the operator is built, and the single-layer tables freed (cell_layers.h).
    layers = std::make_unique<CellLayers>(shapes, grids_, domain, options_.quadrature, lambda != 1.0,
                                          grid_cache_.get(), traction, bring_traction);
    s.owned_cells = layers->owned().size();
    timing.cell_geometry = layers->build_timings().geometry;
    timing.self_corrections = layers->build_timings().self;
    timing.near_corrections = layers->build_timings().near;
  }

  // (12): the wall force for the cells' traction and the velocity U (previous step's).
  std::unique_ptr<CellLayersAtPoints> at_wall;
  if (wall_ && nc > 0) {
    ScopedTimer timer(timing.at_wall_build);
    at_wall = std::make_unique<CellLayersAtPoints>(*layers, wall_->nodes(), traction, bring_traction);
    s.near_wall_points = at_wall->near_points();
  }
  double sweep_tolerance = 0;  // > 0: the start sweeps' looser tolerance (below)
  // The cells' loads' part of <grad p> (above); zero without a box.
  const Eigen::Vector3d loads_gradient =
      options_.domain.box ? Eigen::Vector3d(external_force / options_.domain.box->volume()) : Eigen::Vector3d::Zero();
  // U: at the layers' held rows (layers->nodes()), or empty (none yet).
  auto solve_wall = [&](const Eigen::MatrixXd& U, const PointField& guess) {
    // The cells' velocity at the wall nodes, this rank's part of it (its cells as sources, its
    // slab of the grid): the wall solve sums the ranks' parts, each rank its segment of nodes.
    const PointField none = PointField::Zero(wall_->nodes().rows(), 3);
    PointField v = none;
    if (at_wall) {
      ScopedTimer timer(timing.at_wall_products);
      v -= at_wall->single_layer_part(*traction) / (8 * kPi);
      if (lambda != 1.0 && U.size() > 0) v += (1 - lambda) / (8 * kPi) * at_wall->double_layer_part(U);
    }
    WallSolution w;
    ScopedTimer solve_timer(timing.wall_solve);
    if (options_.pressure_gradient) {
      w = wall_->solve(none, {}, 0, &v);
      s.mean_velocity = wall_->mean_velocity_for(*options_.pressure_gradient - loads_gradient, w.force);
      w.force += wall_->force_for_mean_velocity(s.mean_velocity);
    } else if (options_.tube_velocity) {
      // The guess's <u> part lies in the recycled space of the unit solves (tube_drive.h).
      w = wall_->solve(none, guess, sweep_tolerance, &v);
      const int a = options_.tube->axis;
      const double at_rest = wall_->pressure_gradient(w.force)[a] + loads_gradient[a];
      s.mean_velocity = Eigen::Vector3d::Unit(a) * tube_meter_->mean_velocity_for(*options_.tube_velocity, at_rest);
      w.force += wall_->force_for_mean_velocity(s.mean_velocity);
    } else {
      w = wall_->solve(none.rowwise() + s.mean_velocity.transpose(), guess, sweep_tolerance, &v);
    }
    solve_timer.stop();
    s.wall_force = w.force;
    s.gmres_wall += w.gmres.iterations;
    s.wall_nodes_received += w.nodes_received;
    s.wall_residual = w.gmres.relative_residual;
    s.pressure_gradient = wall_->pressure_gradient(w.force) + loads_gradient;
    if (tube_meter_) {
      const int a = options_.tube->axis;
      s.tube_velocity = tube_meter_->tube_velocity(s.mean_velocity[a], s.pressure_gradient[a]);
    }
  };
  // (10): the cell velocity for the wall force just found. The wall operator at the cell nodes
  // is built once for all the start sweeps.
  std::optional<WallOperator> wall_at_cells;
  // `image`: the left-hand side of (10) at `guess` when known (in: saves a product), and at the
  // solution (out); see solve_cell_velocity.
  auto solve_cells = [&](const Eigen::MatrixXd& guess, Eigen::MatrixXd* image) {
    Eigen::MatrixXd background;
    std::optional<Eigen::MatrixXd> wall_velocity_part;
    if (options_.domain.box) {
      background.resize(static_cast<Eigen::Index>(layers->owned().size()) * np, 3);  // this rank's rows
      background.rowwise() = s.mean_velocity.transpose();
      if (wall_) {
        // Each rank evaluates the wall's near field and real-space sum at its own cells' nodes
        // and the smooth part on its slab of the grid; the ranks' parts add up in the solve.
        // The targets are the held cells' nodes (the step's halo holds every cell its part reaches).
        if (!wall_at_cells) {
          ScopedTimer timer(timing.wall_at_cells_build);
          const SourceRows owned = layers->owned_nodes();
          wall_at_cells.emplace(wall_->operator_at(layers->nodes().x, TargetRows{owned.begin, owned.end},
                                                   options_.domain.ranks, static_cast<long>(nc) * np));
        }
        ScopedTimer timer(timing.wall_at_cells);
        wall_velocity_part = WallCoupling::velocity_at(*wall_at_cells, s.wall_force);  // at the held rows
      }
    } else {
      // Free space: every cell is held (a rank's part reaches every node).
      const SourceNodes& nodes = layers->nodes();
      if (!layers->holds_all()) throw std::logic_error("CellStepper: free-space layers that do not hold every cell");
      background.resize(static_cast<Eigen::Index>(nc) * np, 3);
      for (int r = 0; r < nc * np; ++r) background.row(r) = options_.background(Eigen::Vector3d(nodes.x.row(r)));
    }
    if (!work_arrays_->keeping()) release_heap_memory();  // what the builds freed
    work_arrays_->keep(true);
    ScopedTimer products_timer(timing.cell_products);
    const VelocitySolve v =
        solve_cell_velocity(*layers, *traction, lambda, background, std::max(options_.gmres_tolerance, sweep_tolerance),
                            options_.gmres_max_iterations, guess, image,
                            wall_velocity_part ? &*wall_velocity_part : nullptr);
    products_timer.stop();
    timing.cell_corrections = layers->build_timings().applied;
    const EwaldTimings& ewald = layers->build_timings().double_layer_ewald;
    timing.cell_ewald_real = ewald.real_space;
    timing.cell_ewald_spreading = ewald.smooth.spreading;
    timing.cell_ewald_fft = ewald.smooth.fft + ewald.smooth.influence;
    timing.cell_ewald_interpolation = ewald.smooth.interpolation;
    if (!v.gmres.converged) {
      throw std::runtime_error("GMRES for the cell velocity did not converge" + at_step(step) + ": relative residual " +
                               std::to_string(v.gmres.relative_residual) + " after " +
                               std::to_string(v.gmres.iterations) + " iterations");
    }
    s.velocity = v.velocity;
    s.gmres_cells += v.gmres.iterations;
    s.cell_rows_received += v.rows_received;
    s.cell_residual = v.gmres.relative_residual;
  };

  // The velocities' history is held by the last step's owners (history_owners_): each rank
  // brings the rows its products read into the layers' held layout (zero at the other held
  // rows): its own cells' for the guess of (10) (from another rank only where a cell's owner
  // changed) and, for the cells' double layer at the wall, those of the wall's halo too. On one
  // process the held layout is every cell's rows in owner order.
  Eigen::MatrixXd velocity_guess, previous_velocity;  // this rank's own rows; the held rows
  const bool with_history = nc > 0 && velocities_held() > 0;  // alike on every rank
  if (with_history) {
    const CellOwners& held_by = history_owners_;
    const Communicator& ranks = options_.domain.ranks;
    if (ranks.size() == 1) {
      auto in_owner_order = [&](const Eigen::MatrixXd& held) {
        if (held_by.order == owners.order) return held;
        return owners.to_owner_order(held_by.to_cell_order(held, np), np);
      };
      velocity_guess = in_owner_order(extrapolated_velocity());
      previous_velocity = in_owner_order(state_.previous_velocity);
    } else {
      const int r = ranks.rank();
      std::vector<int> position(static_cast<std::size_t>(nc));  // a cell's, in held_by's order
      for (int k = 0; k < nc; ++k) position[static_cast<std::size_t>(held_by.order[k])] = k;
      auto in_held_by = [&](int k) { return position[static_cast<std::size_t>(owners.order[k])]; };
      std::vector<int> read;  // positions in held_by's order
      for (int k = owners.first[r]; k < owners.first[r + 1]; ++k) read.push_back(in_held_by(k));
      if (at_wall && lambda != 1.0)
        for (int k : layers->halo_with(at_wall->slabs())) read.push_back(in_held_by(k));
      std::sort(read.begin(), read.end());
      std::vector<int> rows;
      for (int p : read)
        for (int i = 0; i < np; ++i) rows.push_back(p * np + i);
      // Held here: the cells the last step's owners gave this rank (its own in that layout)
      // and the layers' held cells, in held_by's order.
      std::vector<int> hold;
      for (int p = held_by.first[r]; p < held_by.first[r + 1]; ++p) hold.push_back(p);
      for (int k : layers->held_cells()) hold.push_back(in_held_by(k));
      std::sort(hold.begin(), hold.end());
      hold.erase(std::unique(hold.begin(), hold.end()), hold.end());
      OwnedRows holders(held_by.first, np, ranks);
      holders.hold(hold);
      holders.read_only(rows);
      // From holders' held layout to the layers' (the same cells, in owner order).
      auto at_layers_rows = [&](const Eigen::MatrixXd& held) {
        const Eigen::MatrixXd brought = holders.gather_read_held(held);
        Eigen::MatrixXd out(layers->nodes().size(), 3);
        for (int k : layers->held_cells()) {
          const auto at = std::lower_bound(hold.begin(), hold.end(), in_held_by(k)) - hold.begin();
          out.middleRows(layers->held_row(k), np) = brought.middleRows(static_cast<Eigen::Index>(at) * np, np);
        }
        return out;
      };
      velocity_guess = rows_of_owned(holders.gather_read_held(extrapolated_velocity()), held_by, owners, r, np, hold);
      previous_velocity = at_layers_rows(state_.previous_velocity);
    }
  }
  try {
    const bool start_sweeps = wall_ && nc > 0 && lambda != 1.0 && !with_history;
    if (start_sweeps) sweep_tolerance = kStartSweepForcing;  // U = 0 in (12): an O(1) change to come
    if (wall_) solve_wall(previous_velocity, force_guess);  // empty without history
    Eigen::MatrixXd image;  // of the cell velocity under (10)'s left-hand side
    if (nc > 0) solve_cells(velocity_guess, start_sweeps ? &image : nullptr);
    // The first step has no U^{n-1} for the double layer in (12): sweep (12) and (10) until U
    // settles (to kStartSweepTolerance: later steps lag U by one step, an O(dt) error, anyway),
    // so that the run starts close to the solution of the coupled system (9). The sweep map
    // U -> U' is affine; Anderson mixing turns its plain iteration (a contraction by ~0.5 a
    // sweep in a tube at H_T = 0.3) into a Krylov method. Each sweep's solves stop at
    // kStartSweepForcing times the last change of U (an inexact fixed-point iteration, in the
    // manner of Eisenstat & Walker's forcing terms), the last at the solves' own tolerances.
    // Each U is a combination of the solved velocities, so the mixing also combines their
    // images under (10)'s operator, which GMRES returns: a sweep's solve starts from U without
    // a product. The sweeps (the first step only) hold, as GMRES does, this rank's own cells'
    // rows of U, their history and their images, and mix them with inner products summed over
    // the ranks; (12) reads U at the rows of the wall's halo too, brought from their owners.
    if (start_sweeps) {
      const Communicator& ranks = options_.domain.ranks;
      OwnedRows by_owners(owners.first, np, ranks);
      if (ranks.size() > 1) {
        const int r = ranks.rank();
        std::vector<int> read;
        for (int k = owners.first[r]; k < owners.first[r + 1]; ++k) read.push_back(k);
        for (int k : layers->halo_with(at_wall->slabs())) read.push_back(k);
        std::vector<int> rows;
        for (int k : read)
          for (int i = 0; i < np; ++i) rows.push_back(k * np + i);
        std::sort(rows.begin(), rows.end());
        by_owners.hold(layers->held_cells());
        by_owners.read_only(rows);
      }
      auto at_wall_rows = [&](const Eigen::MatrixXd& mine) {  // the layers' held rows
        return ranks.size() == 1 ? mine : by_owners.gather_read_held(mine);
      };
      const SplitInnerProducts split{ranks};
      auto norm = [&](const Eigen::MatrixXd& mine) {
        return split.norm(Eigen::Map<const Eigen::VectorXd>(mine.data(), mine.size()));
      };
      AndersonMixing mixing(kStartSweepDepth, [&](Eigen::VectorXd& parts) { split.sum(parts); });
      Eigen::MatrixXd U = Eigen::MatrixXd::Zero(s.velocity.rows(), 3);  // the U of the first solve's (12)
      Eigen::MatrixXd u = s.velocity;
      const double settled = std::max(kStartSweepTolerance, 10 * options_.gmres_tolerance);
      const double finest = std::min(options_.gmres_tolerance, options_.wall_solve.tolerance);
      for (int sweep = 0; sweep < kMaxStartSweeps; ++sweep) {
        sweep_tolerance = kStartSweepForcing * norm(u - U) / norm(u);
        if (sweep_tolerance <= finest) sweep_tolerance = 0;
        U = mixing.next(U, u, image, image);
        solve_wall(at_wall_rows(U), s.wall_force);
        solve_cells(U, &image);
        u = s.velocity;
        s.start_sweeps = sweep + 1;
        if (norm(u - U) <= settled * norm(U) && sweep_tolerance == 0) break;
      }
      sweep_tolerance = 0;
    }
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    if (what.find(" at step ") != std::string::npos) throw;
    throw std::runtime_error(what + at_step(step));
  }
  // U^n held by its owners in the products: the flux sections' double layer brings its halo's
  // rows; each rank keeps its own cells' (the velocities' history), not every cell's.
  std::optional<HaloDensity> velocity;
  if (nc > 0) velocity.emplace(std::move(s.velocity), owners, np, options_.domain.ranks, held_cells);
  if (section_meter_) {
    std::vector<SHSurface> own;  // the layers' owned cells: owners' block of this rank
    const int rank = options_.domain.ranks.rank();
    for (int k = owners.first[rank]; k < owners.first[rank + 1]; ++k) own.push_back(SHSurface(shapes[k]));
    DensityHalo bring_densities = [&](const std::vector<int>& halo) {
      bring_traction(halo);
      if (lambda != 1.0) velocity->bring(halo);  // the double layer's density
    };
    const CellsAtStep cells_now{layers.get(), traction, velocity ? &velocity->density() : nullptr, &own,
                                nc > 0 ? grids_->n_grid.get() : nullptr, lambda, bring_densities};
    s.section_flux = section_meter_->fluxes(s.mean_velocity, s.wall_force, nc > 0 ? &cells_now : nullptr);
  }
  if (layers) {
    // The step's halo: the layers' and the cells whose stencils reach this rank's slabs of the
    // grids of the layers at the wall and at the flux sections (their densities read) and of
    // the wall at the cells (their rows of its part), as foreseen before they were built.
    if (at_wall) check_built_slabs(at_wall->slabs(), other_slabs, "the cells' layers at the wall");
    if (section_meter_) check_built_slabs(section_meter_->slabs(), other_slabs, "the cells' layers at the sections");
    if (wall_at_cells)
      if (const std::optional<SlabPlanes> slab = rank_slab(wall_at_cells->grid()))
        check_built_slabs({*slab}, other_slabs, "the wall at the cells");
    // The halo named before the layers were built must be the one they name (cell_layers_halo):
    // the cells a rank will hold besides its own are chosen by it.
    if (layers->halo_with(other_slabs) != step_halo)
      throw std::logic_error("CellStepper: the step's halo named before its layers were built is not theirs" + at_step(step));
    s.halo_cells = static_cast<int>(step_halo.size());
  }
  if (velocity) {
    s.velocity = velocity->owned();
    s.velocity_rows_received = velocity->rows_received();
  }
  if (step_traction) {
    s.traction_rows_received = step_traction->rows_received();
    s.traction = step_traction->release();
  }
  s.owners = std::move(owners);
  total_timer.stop();
  if (layers) layers->report_memory(s.memory);
  if (at_wall) at_wall->report_memory(s.memory, "at wall:");
  if (wall_at_cells) wall_at_cells->report_memory(s.memory, "wall at cells");
  if (wall_) wall_->report_memory(s.memory);
  s.memory.add("cell SPME grids", grid_cache_->memory_bytes());
  // The cells' state held on this rank between steps (docs/scaling.md): the shapes of the cells
  // it moved last, its owned cells' traction on the N grid and this step's velocity, the
  // membrane states of its cells in the products and its own cells' last three velocities
  // (every cell's on one rank).
  std::size_t cells_held = matrix_bytes(s.traction) + matrix_bytes(s.velocity) +
                           matrix_bytes(state_.previous_velocity) + matrix_bytes(state_.older_velocity) +
                           matrix_bytes(state_.oldest_velocity);
  for (const Cell& c : cells_) cells_held += matrix_bytes(c.shape.coeffs().values());
  for (const MembraneState& m : s.membrane)
    cells_held += matrix_bytes(m.traction.values()) + matrix_bytes(m.traction_grid) + matrix_bytes(m.dilatation) +
                  matrix_bytes(m.principal_tension);
  s.memory.add("the cells' shapes, membranes, velocities held", cells_held);
  std::set<const RestMetrics*> rest_metrics;  // shared by the cells placed as copies of one shape
  for (const Cell& c : cells_)
    if (rest_metrics.insert(c.membrane->rest_metrics().get()).second)
      s.memory.add("membranes' rest metrics", c.membrane->rest_metrics()->memory_bytes());
  return s;
}

double CellStepper::enforce_volume(int c) {
  // Move the surface along its normal by the uniform delta = (V0 - V) / A (twice: the
  // correction is first order), the variational volume constraint of section 10.2.
  double restored = 0.0;
  for (int it = 0; it < 2; ++it) {
    const SurfaceGeometry g = cells_[c].shape.geometry(*grids_->n_grid);
    const double deficit = state_.volume0[c] - enclosed_volume(g);
    if (it == 0) restored = std::abs(deficit) / state_.volume0[c];
    const double delta = deficit / surface_area(g);
    const Eigen::MatrixXd shift = delta * g.normal;
    cells_[c].shape.coeffs().values() += grids_->n_grid->analyze(shift).values();
  }
  return restored;
}

void CellStepper::move_cells(const FlowSolution& s, StepReport& report) {
  const int nc = static_cast<int>(cells_.size());
  const int np = points_per_cell();
  const SHTransform& tn = *grids_->n_grid;
  // X^{n+1} = X^n + dt U^n (eq. 11), or AB2 with U^{n-1}.
  const bool ab2 = options_.scheme == TimeScheme::ab2 && velocities_held() > 0;
  // Each rank moves, separates (collision.h: it brings the shapes of the others' cells near its
  // own) and corrects its own cells in the step's products (s.owners: it holds their
  // velocities), the ranks sharing the shapes at the end; a cell that became invalid on one
  // rank stops every rank (the first one named).
  const Communicator& ranks = options_.domain.ranks;
  const CellOwners& owners = s.owners;
  const int first = owners.first[ranks.rank()], end = owners.first[ranks.rank() + 1];
  auto stop_if_invalid = [&](int first_invalid) {
    first_invalid = static_cast<int>(ranks.min(first_invalid));
    if (first_invalid < nc)
      throw std::runtime_error("cell " + std::to_string(first_invalid) + " became invalid (NaN)" +
                               at_step(state_.steps + 1));
  };
  int first_invalid = nc;
  const Eigen::MatrixXd velocity = owned_velocity(s);
  for (int k = first; k < end; ++k) {
    const int c = owners.order[k];
    const SHCoeffs rate = tn.analyze(velocity.middleRows((k - first) * np, np));
    Eigen::MatrixXd& x = cells_[c].shape.coeffs().values();
    if (ab2) {  // U^{n-1} at s.owners' cells (migrate_history)
      const SHCoeffs previous = tn.analyze(state_.previous_velocity.middleRows((k - first) * np, np));
      x += options_.dt * (1.5 * rate.values() - 0.5 * previous.values());
    } else {
      x += options_.dt * rate.values();
    }
    if (!x.allFinite()) first_invalid = std::min(first_invalid, c);
  }
  stop_if_invalid(first_invalid);
  if (options_.collision_threshold > 0) {
    // In owner order, so that each rank pushes its own cells (remove_collisions takes
    // owned_block's blocks of the shapes it is given); the others' are the last step's here.
    std::vector<SHSurface> shapes;
    for (const int c : owners.order) shapes.push_back(cells_[c].shape);
    const Eigen::Vector3d period = options_.domain.box ? options_.domain.box->lengths() : Eigen::Vector3d::Zero();
    CollisionReport k = remove_collisions(shapes, tn, period, wall_distance_.get(), options_.collision_threshold, ranks);
    if (k.closest_cell >= 0) k.closest_cell = owners.order[k.closest_cell];
    if (k.closest_other >= 0) k.closest_other = owners.order[k.closest_other];
    // Surfaces left crossing (each other or the wall) make the boundary integrals meaningless
    // and the run blows up some steps later: stop here, at the last checkpoint's state.
    if (!k.converged && k.min_separation < 0) {
      const std::string where = k.closest_other < 0 ? "cell " + std::to_string(k.closest_cell) + " and the wall"
                                                     : "cells " + std::to_string(k.closest_cell) + " and " +
                                                           std::to_string(k.closest_other);
      throw std::runtime_error("collision removal left cell surfaces crossing after " + std::to_string(k.passes) +
                               " passes (smallest separation " + std::to_string(k.min_separation) + ", " + where +
                               ", h_s = " +
                               std::to_string(options_.collision_threshold) + ")" + at_step(state_.steps + 1) +
                               ": the cells moved into each other (or the wall) faster than the removal separates "
                               "them; try a smaller time step or a higher order of the cells");
    }
    for (int i = first; i < end; ++i) cells_[owners.order[i]].shape = std::move(shapes[i]);
    report.collision_pairs = k.cell_pairs;
    report.wall_contacts = k.wall_contacts;
    report.collision_displacement = k.max_displacement;
  }
  double volume_correction = 0.0;
  for (int k = first; k < end; ++k) {
    const int c = owners.order[k];
    if (options_.volume_constraint) volume_correction = std::max(volume_correction, enforce_volume(c));
    const SurfaceGeometry g = cells_[c].shape.geometry(tn);
    const double dv = std::abs(enclosed_volume(g) / state_.volume0[c] - 1.0);
    const double da = std::abs(surface_area(g) / state_.area0[c] - 1.0);
    if (!std::isfinite(dv) || !std::isfinite(da)) {
      first_invalid = std::min(first_invalid, c);
      continue;
    }
    report.max_volume_error = std::max(report.max_volume_error, dv);
    report.max_area_error = std::max(report.max_area_error, da);
  }
  stop_if_invalid(first_invalid);
  report.max_volume_error = largest(report.max_volume_error, ranks);
  if (options_.volume_constraint) report.max_volume_correction = largest(volume_correction, ranks);
  report.max_area_error = largest(report.max_area_error, ranks);
}

std::vector<Eigen::Vector3d> CellStepper::volume_centroids() const {
  if (cells_.empty()) return {};
  return rbcflow::volume_centroids(cells_, *grids_->n_grid, history_owners_, options_.domain.ranks);
}

std::vector<CellMeasures> CellStepper::cell_measures(const FlowSolution& s) const {
  if (cells_.empty()) return {};
  const Communicator& ranks = options_.domain.ranks;
  if (ranks.size() == 1) return rbcflow::cell_measures(cells_, *grids_->n_grid, owned_velocity(s), s.owners, ranks);
  // The shapes of this rank's cells in s.owners, brought where held by another (held_shapes.h).
  std::vector<Cell> cells = cells_;
  std::vector<int> own(s.owners.order.begin() + s.owners.first[ranks.rank()],
                       s.owners.order.begin() + s.owners.first[ranks.rank() + 1]);
  bring_shapes(shapes_of(cells), history_owners_, own, ranks);
  return rbcflow::cell_measures(cells, *grids_->n_grid, owned_velocity(s), s.owners, ranks);
}

double CellStepper::discharge_hematocrit(const FlowSolution& s, const std::vector<SHSurface>& own) const {
  const int a = options_.tube->axis;
  const double radius = options_.tube->radius;
  const double tube_flux = *s.tube_velocity * std::numbers::pi * radius * radius;
  return cells_volume_flux(own, owned_velocity(s), *grids_->n_grid, a, options_.domain.ranks) /
         (options_.domain.box->lengths()[a] * tube_flux);
}

StepReport CellStepper::advance(const FlowSolution& s) {
  StepReport report;
  report.gmres_iterations = s.gmres_cells;
  report.gmres_residual = s.cell_residual;
  report.gmres_wall = s.gmres_wall;
  report.wall_residual = s.wall_residual;
  report.mean_velocity = s.mean_velocity;
  report.pressure_gradient = s.pressure_gradient;
  const int nc = static_cast<int>(cells_.size());
  for (int c = 0; c < static_cast<int>(s.membrane.size()); ++c) {  // the rank's own cells' (the others' are empty)
    const MembraneState& m = s.membrane[c];
    if (m.dilatation.size() == 0) continue;
    const double strain = (m.dilatation.array() - 1.0).abs().maxCoeff();
    if (report.max_area_strain_cell < 0 || strain > report.max_area_strain) {
      report.max_area_strain = strain;
      report.max_area_strain_cell = c;
    }
  }
  const double strain = largest(report.max_area_strain, options_.domain.ranks);
  if (nc > 0) {
    const int holder = report.max_area_strain_cell >= 0 && report.max_area_strain == strain ? report.max_area_strain_cell : nc;
    report.max_area_strain_cell = static_cast<int>(options_.domain.ranks.min(holder));
  }
  report.max_area_strain = strain;
  report.tube_velocity = s.tube_velocity;
  report.section_flux = s.section_flux;
  report.contact = s.contact;
  if (!cells_.empty()) migrate_shapes(s.owners);  // the shapes of this rank's cells in s.owners, no others
  if (!cells_.empty() && wall_) {  // the cells in their vessel at X^n
    // The gap, hematocrit and cell-free layer of each rank's own cells in the step's products
    // (it holds their velocities), reduced over the ranks.
    const int rank = options_.domain.ranks.rank();
    std::vector<SHSurface> own;
    std::vector<Eigen::MatrixX3d> points;
    for (int k = s.owners.first[rank]; k < s.owners.first[rank + 1]; ++k) {
      own.push_back(cells_[s.owners.order[k]].shape);
      points.push_back(grids_->n_grid->synthesize(own.back().coeffs()));
    }
    report.min_wall_gap = options_.domain.ranks.min(smallest_wall_distance(*wall_distance_, points));
    if (s.tube_velocity && options_.tube->whole_period) report.discharge_hematocrit = discharge_hematocrit(s, own);
    if (options_.tube && options_.tube->whole_period) {
      report.cell_free_layer = cell_free_layer(own, *grids_->n_grid, *options_.tube,
                                               options_.domain.box->lengths()[options_.tube->axis], {},
                                               options_.domain.ranks);
    }
  }
  if (!cells_.empty()) {
    migrate_history(s.owners);  // U^{n-1} for AB2's move; the history with U^n held alike
    move_cells(s, report);
  }
  state_.oldest_velocity = std::move(state_.older_velocity);
  state_.older_velocity = std::move(state_.previous_velocity);
  state_.older_wall_force = std::move(state_.previous_wall_force);
  if (!cells_.empty()) {
    state_.previous_velocity = owned_velocity(s);
  } else {
    state_.previous_velocity = s.velocity;
  }
  state_.previous_wall_force = s.wall_force;
  state_.time += options_.dt;
  ++state_.steps;
  return report;
}

void CellStepper::migrate_shapes(const CellOwners& to) {
  const Communicator& ranks = options_.domain.ranks;
  if (ranks.size() == 1) return;
  const int r = ranks.rank();
  std::vector<int> own(to.order.begin() + to.first[r], to.order.begin() + to.first[r + 1]);
  bring_shapes(shapes_of(cells_), history_owners_, own, ranks);
  std::vector<char> mine(cells_.size(), 0);
  for (int c : own) mine[static_cast<std::size_t>(c)] = 1;
  for (std::size_t c = 0; c < cells_.size(); ++c)
    if (!mine[c]) release_shape(cells_[c].shape.coeffs());
}

int CellStepper::velocities_held() const {
  int held = 0;
  for (const Eigen::MatrixXd* u : {&state_.previous_velocity, &state_.older_velocity, &state_.oldest_velocity}) {
    if (u->cols() != 3) break;
    ++held;
  }
  return held;
}

Eigen::MatrixXd CellStepper::owned_velocity(const FlowSolution& s) const {
  const int nc = static_cast<int>(cells_.size());
  const int np = points_per_cell();
  const Communicator& ranks = options_.domain.ranks;
  const CellOwners& owners = s.owners;
  if (owners.order.size() != static_cast<std::size_t>(nc) || owners.first.size() != static_cast<std::size_t>(ranks.size()) + 1)
    throw std::invalid_argument("advance: not this stepper's solution (its owners are another's)");
  const Eigen::Index owned = static_cast<Eigen::Index>(owners.first[ranks.rank() + 1] - owners.first[ranks.rank()]) * np;
  // As solve() leaves it; where the rank owns every cell, owner order is the cells' own.
  if (s.velocity.rows() == owned) return s.velocity;
  if (s.velocity.rows() != static_cast<Eigen::Index>(nc) * np)
    throw std::invalid_argument("advance: not this stepper's solution");
  return rows_of_owned(s.velocity, owners_by_block(nc, 1), owners, ranks.rank(), np);  // every cell's rows
}

void CellStepper::migrate_history(const CellOwners& to) {
  const Communicator& ranks = options_.domain.ranks;
  const int held = velocities_held();
  if (ranks.size() == 1 || held == 0 || (to.order == history_owners_.order && to.first == history_owners_.first)) {
    history_owners_ = to;
    return;
  }
  const int nc = static_cast<int>(cells_.size());
  const int np = points_per_cell();
  std::vector<int> position(static_cast<std::size_t>(nc));  // in history_owners_' order
  for (int k = 0; k < nc; ++k) position[static_cast<std::size_t>(history_owners_.order[k])] = k;
  // Brought into the held layout of the rank's old and new cells, not a matrix of every row.
  const int r = ranks.rank();
  std::vector<int> read, hold;  // positions in history_owners_' order
  for (int k = to.first[r]; k < to.first[r + 1]; ++k) read.push_back(position[static_cast<std::size_t>(to.order[k])]);
  std::sort(read.begin(), read.end());
  for (int p = history_owners_.first[r]; p < history_owners_.first[r + 1]; ++p) hold.push_back(p);
  hold.insert(hold.end(), read.begin(), read.end());
  std::sort(hold.begin(), hold.end());
  hold.erase(std::unique(hold.begin(), hold.end()), hold.end());
  std::vector<int> rows;
  for (int p : read)
    for (int i = 0; i < np; ++i) rows.push_back(p * np + i);
  OwnedRows holders(history_owners_.first, np, ranks);
  holders.hold(hold);
  holders.read_only(rows);
  Eigen::MatrixXd* history[] = {&state_.previous_velocity, &state_.older_velocity, &state_.oldest_velocity};
  for (int h = 0; h < held; ++h)
    *history[h] = rows_of_owned(holders.gather_read_held(*history[h]), history_owners_, to, r, np, hold);
  history_owners_ = to;
}

Eigen::MatrixXd CellStepper::extrapolated_velocity() const {
  switch (velocities_held()) {
    case 1: return state_.previous_velocity;
    case 2: return 2 * state_.previous_velocity - state_.older_velocity;
    default: return 3 * (state_.previous_velocity - state_.older_velocity) + state_.oldest_velocity;
  }
}

StepperState CellStepper::state() const {
  StepperState s = state_;
  for (const Cell& c : cells_) s.shapes.push_back(c.shape.coeffs());
  if (cells_.empty()) return s;
  std::vector<SHCoeffs*> shapes;
  for (SHCoeffs& x : s.shapes) shapes.push_back(&x);
  share_shapes(shapes, history_owners_, options_.domain.ranks);
  const OwnedRows holders(history_owners_.first, points_per_cell(), options_.domain.ranks);
  for (Eigen::MatrixXd* u : {&s.previous_velocity, &s.older_velocity, &s.oldest_velocity})
    if (u->cols() == 3) *u = history_owners_.to_cell_order(holders.gather(*u), points_per_cell());
  return s;
}

StepperState CellStepper::held_state() const {
  const Communicator& ranks = options_.domain.ranks;
  if (ranks.size() == 1 || cells_.empty()) return state();
  StepperState s = state_;
  StepperState::Part part{history_owners_.order, history_owners_.first[ranks.rank()],
                          history_owners_.first[ranks.rank() + 1], points_per_cell()};
  std::vector<char> mine(cells_.size(), 0);
  for (int p = part.begin; p < part.end; ++p) mine[static_cast<std::size_t>(part.order[p])] = 1;
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    const SHCoeffs& x = cells_[c].shape.coeffs();
    s.shapes.push_back(mine[c] ? x : shape_not_held(x.order()));
  }
  s.part = std::move(part);
  return s;
}

void CellStepper::restore(const StepperState& s) {
  const std::size_t nc = cells_.size();
  const int np = points_per_cell();
  const Communicator& ranks = options_.domain.ranks;
  if (s.shapes.size() != nc || s.volume0.size() != nc || s.area0.size() != nc)
    throw std::invalid_argument("restore: the state has " + std::to_string(s.shapes.size()) + " cells, the run " +
                                std::to_string(nc));
  for (std::size_t c = 0; c < nc; ++c) {
    if (s.shapes[c].order() != cells_[c].shape.coeffs().order())
      throw std::invalid_argument("restore: cell " + std::to_string(c) + " has another spherical-harmonic order");
  }
  // A rank's part: the cells of owned_block's block of the part's order, this rank's.
  const OwnedRange block = owned_block(static_cast<int>(nc), ranks);
  if (s.part && (s.part->order.size() != nc || s.part->begin != block.begin || s.part->end != block.end))
    throw std::invalid_argument("restore: a part of the state read for another rank");
  const long held_rows = static_cast<long>(s.part ? block.size() : static_cast<int>(nc)) * np;
  for (const Eigen::MatrixXd* u : {&s.previous_velocity, &s.older_velocity, &s.oldest_velocity}) {
    if (u->size() && (u->rows() != held_rows || u->cols() != 3))
      throw std::invalid_argument("restore: a previous velocity does not fit the cells");
  }
  for (const PointField* f : {&s.previous_wall_force, &s.older_wall_force}) {
    if (f->size() && (!wall_ || f->rows() != wall_->elements().num_nodes()))
      throw std::invalid_argument("restore: a previous wall force does not fit the wall");
  }
  state_ = s;
  state_.shapes.clear();  // held once, in the cells
  state_.part.reset();
  for (std::size_t c = 0; c < nc; ++c) cells_[c].shape.coeffs() = s.shapes[c];
  history_owners_ = owners_by_block(static_cast<int>(nc), ranks.size());
  if (s.part) {  // the velocities are this rank's rows already, of the cells in the part's order
    history_owners_.order = s.part->order;
    return;
  }
  for (Eigen::MatrixXd* u : {&state_.previous_velocity, &state_.older_velocity, &state_.oldest_velocity}) {
    if (u->size() == 0) {
      u->resize(0, 0);  // absent
    } else {
      *u = u->middleRows(block.begin * np, block.size() * np).eval();  // this rank's block
    }
  }
}

}  // namespace rbcflow
