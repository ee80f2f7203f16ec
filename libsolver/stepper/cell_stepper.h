#pragma once
// Time advancement of cells among vessel walls, the staggered scheme of section 2:
//   solve():   membrane traction on the de-aliasing grid (eq. 22-23) minus any body-force
//              density and the contact repulsion's (contact_force.h); the wall force F^n from (12) with U^{n-1}; the cell velocity U^n
//              from (10) with F^n (GMRES; lambda = 1 is explicit);
//   advance(): X^{n+1} = X^n + dt U^n (forward Euler, eq. 11) or second-order
//              Adams-Bashforth, then the kinematic collision removal of section 11.2
//              (threshold h_s, collision.h) and the volume constraint of section 10.2 (a
//              normal correction of each cell to its initial volume).
// solve() does not change the state, so output written between the two (or a frame of the
// final state) leaves a run bit-for-bit the same; step() is solve() then advance().
// Periodic mode is driven by <u> (or a prescribed <grad p>, eq. 8, or a tube velocity held
// every step, tube_drive.h); free space (no walls) by
// an imposed background flow. Without cells a step is one quasi-steady wall solve.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "libsolver/membrane/membrane_force.h"
#include "libsolver/operators/cell_layers.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/stepper/cell_velocity.h"
#include "libsolver/stepper/collision.h"
#include "libsolver/stepper/contact_force.h"
#include "libsolver/stepper/section_flux.h"
#include "libsolver/stepper/state_archive.h"
#include "libsolver/stepper/step_timings.h"
#include "libsolver/stepper/tube_drive.h"
#include "libsolver/stepper/wall_coupling.h"

namespace rbcflow {

enum class TimeScheme { euler, ab2 };

struct CellStepperOptions {
  double dt = 1e-3;
  TimeScheme scheme = TimeScheme::euler;
  double viscosity_ratio = 1.0;
  LayerDomain domain;                     // periodic box (mean velocity below) or free space
  Eigen::Vector3d mean_velocity = Eigen::Vector3d::Zero();        // <u> of eq. (6), periodic
  std::optional<Eigen::Vector3d> pressure_gradient;               // prescribed <grad p> instead
  std::optional<TubeSection> tube;        // a tube section: its mean velocity measured every step
  std::optional<double> tube_velocity;    // or that tube velocity held every step (needs `tube`)
  // Branches whose volume flux is measured every step, each by its candidate cross-sections
  // (section_flux.h; needs a wall).
  std::vector<std::vector<SectionQuadrature>> flux_sections;
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> background;  // free space: u_inf(x)
  double gmres_tolerance = 1e-6;
  int gmres_max_iterations = 100;
  bool volume_constraint = false;
  double collision_threshold = 0.0;       // h_s; 0: no collision removal
  ContactLaw contact;                     // repulsion between membranes and from the wall (contact_force.h); inactive by default
  QuadratureOptions quadrature;
  std::shared_ptr<const WallElements> wall;  // none: no vessel (periodic box only)
  WallSolveOptions wall_solve;
};

struct CellMeasures;  // cell_measures.h

// What CellStepper::cells_for_output brings a rank: the state of the cells it writes.
struct CellsForOutput {
  std::vector<int> cells;                // ascending cell numbers
  std::vector<SHSurface> shapes;         // X^n, one a cell of `cells`
  std::vector<MembraneState> membranes;  // at X^n
  Eigen::MatrixXd velocity, traction;    // U^n and f^n, stacked over `cells` (nodes x 3)
};

struct Cell {
  SHSurface shape;                       // current surface, order N
  std::shared_ptr<const Membrane> membrane;
  Eigen::Vector3d body_force = Eigen::Vector3d::Zero();  // net external force on the cell
};

// What solve() found for the current state (X^n).
struct FlowSolution {
  // U^n, stacked over cells (nodes x 3). On several ranks solve() leaves the rows of this rank's
  // own cells in the products, in owner order (`owners`: the cells advance() moves, whose rows
  // the GMRES of (10) ended with here); CellStepper::cells_for_output brings the rows output reads.
  Eigen::MatrixXd velocity;
  // Hydrodynamic traction f^n on the cells, stacked. On several ranks solve() leaves the rows of
  // this rank's own cells in the products, in owner order, as of the velocity.
  Eigen::MatrixXd traction;
  // Per cell. On several ranks solve() fills only the rank's own cells in the products (owners)
  // and leaves the others empty.
  std::vector<MembraneState> membrane;
  CellOwners owners;          // the cells' owners in the step's products (cell_owners.h)
  PointField wall_force;      // F^n at the wall nodes (empty without a wall)
  Eigen::Vector3d mean_velocity = Eigen::Vector3d::Zero();      // <u> used
  Eigen::Vector3d pressure_gradient = Eigen::Vector3d::Zero();  // (8); zero without a wall
  std::optional<double> tube_velocity;  // U through the options' tube section
  std::vector<double> section_flux;     // through each of the options' flux_sections branches
  int gmres_cells = 0, gmres_wall = 0;
  int start_sweeps = 0;       // the first step's sweeps of (12) and (10) (lambda != 1 with a wall)
  double cell_residual = 0.0, wall_residual = 0.0;
  int near_wall_points = 0;   // wall nodes that needed a nearly-singular cell correction
  // The contact repulsion's (contact_force.h; all zero without it): over every rank's own cells.
  std::optional<ContactReport> contact;
  long cell_rows_received = 0;  // node rows the products of (10) brought this rank from the others
  long traction_rows_received = 0;  // node rows of the traction the step's operators brought it (halo_density.h)
  long velocity_rows_received = 0;  // node rows of U^n brought it: the flux sections' halo, its block of the cells
  int shapes_received = 0;  // cells' shapes brought this rank for the step's products (held_shapes.h)
  int owned_cells = 0, halo_cells = 0;  // this rank's cells in the step's products and their halo in all of them (CellLayers::halo_with)
  long wall_nodes_received = 0;  // wall nodes (12)'s solves brought this rank from the others (WallSolution's)
  StepTimings timings;        // where solve() spent its time
  MemoryReport memory;        // what solve()'s operators held at its end (memory_report.h)
};

struct StepReport {
  int gmres_iterations = 0;   // cells
  double gmres_residual = 0.0;
  int gmres_wall = 0;
  double wall_residual = 0.0;
  Eigen::Vector3d mean_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d pressure_gradient = Eigen::Vector3d::Zero();
  double max_volume_error = 0.0;  // relative to each cell's initial volume, after the step
  // With the volume constraint (section 10.2): the largest |V0 - V| / V0 it restored, V the
  // volume after the move and the collision removal. It is the step's volume error the
  // constraint hides from max_volume_error: the discretisation's, as the continuous flow
  // keeps a closed membrane's volume. Empty without the constraint.
  std::optional<double> max_volume_correction;
  double max_area_error = 0.0;
  // Largest local area strain |J_S - 1| over the cells' membranes (N grid), before the step.
  double max_area_strain = 0.0;
  int max_area_strain_cell = -1;  // the cell that has it (the first of several); -1 without cells
  // Through the options' tube section: the tube velocity U, and with cells in a tube along the
  // whole period the discharge hematocrit H_D = Q_cells / Q_tube (the cells' flux averaged
  // over the period, cell_flux.h).
  std::optional<double> tube_velocity, discharge_hematocrit;
  std::vector<double> section_flux;  // through the options' flux sections (FlowSolution's)
  std::optional<double> cell_free_layer;  // with cells in a tube along the whole period (cell_free_layer.h)
  // With a wall and cells: the smallest distance of a cell's grid point from the wall, before
  // the step (negative: through it). Against the wall's element size: is the gap resolved?
  std::optional<double> min_wall_gap;
  // Collision removal (section 11.2), when h_s > 0: cell pairs (periodic images included) and
  // cells at the wall found closer than h_s, and the largest displacement of a grid point.
  int collision_pairs = 0;
  int wall_contacts = 0;
  double collision_displacement = 0.0;
  // The contact repulsion at X^n (contact_force.h), when the options have one.
  std::optional<ContactReport> contact;
};

// Everything a run needs to continue exactly (checkpoints): the shapes X^n, U^{n-1} and F^{n-1}
// (the staggered coupling and AB2 use them), and U^{n-2}, U^{n-3}, F^{n-2}: the GMRES initial
// guesses 3 U^{n-1} - 3 U^{n-2} + U^{n-3} and 2 F^{n-1} - F^{n-2}.
struct StepperState {
  // Writes or reads every field under its checkpoint name (state_archive.h); throws
  // std::invalid_argument when a cell's coefficients are not those of an order. Reading with
  // `ranks` of more than one, each rank reads only its part (`part`): owned_block's block of
  // the cells in the order of the velocities' rows (cell order where the state was written
  // whole), those cells' coefficients and rows; every other cell keeps its order and no
  // coefficients.
  void archive(StateArchive& a, const Communicator* ranks = nullptr);

  double time = 0.0;
  long steps = 0;
  std::vector<SHCoeffs> shapes;
  Eigen::MatrixXd previous_velocity;  // empty before the first step
  PointField previous_wall_force;     // empty before the first step or without a wall
  Eigen::MatrixXd older_velocity;     // empty before the second step
  PointField older_wall_force;        // empty before the second step or without a wall
  Eigen::MatrixXd oldest_velocity;    // empty before the third step
  std::vector<double> volume0, area0;

  // A rank's part of the state on several ranks, written by the ranks together
  // (CellStepper::save) or read by each (archive() with ranks, CellStepper::load): the cells in
  // the order of the velocities' rows (every rank's, rank 0's first) and this rank's block of
  // them, [begin, end). `shapes` then hold those cells' shapes (the others keep their order and
  // no coefficients) and the velocities those cells' rows. Without it the state is whole, in
  // cell order.
  struct Part {
    std::vector<int> order;
    int begin = 0, end = 0;
    int points_per_cell = 0;
  };
  std::optional<Part> part;
};

class CellStepper {
 public:
  CellStepper(std::vector<Cell> cells, std::shared_ptr<const CellGrids> grids, CellStepperOptions options);

  FlowSolution solve() const;
  StepReport advance(const FlowSolution& s);
  StepReport step() { return advance(solve()); }
  // The state of `cells` (cell numbers) at X^n and U^n of `s` (this stepper's solve(), before
  // advance()), for output: their shapes, membrane states and rows of the velocity and the
  // traction, brought from the ranks that hold them (each only its own cells' between steps).
  // Collective: each rank names the cells it writes (a frame writer of rbcflow.h5 its block of
  // the cells, rank 0 every cell for the VTK frames and renders); a rank may name none.
  CellsForOutput cells_for_output(const FlowSolution& s, std::vector<int> cells) const;

  double time() const { return state_.time; }
  long steps() const { return state_.steps; }
  double dt() const { return options_.dt; }
  // The <u> that drives a periodic flow at the start (where a tube velocity is held, the
  // cell-free one: each step's own is in its FlowSolution).
  const Eigen::Vector3d& mean_velocity() const { return options_.mean_velocity; }
  // Every cell; on several ranks only the shapes of this rank's own cells (those it moved last,
  // or read by load()) are held between steps (held_shapes.h: the others keep their order and
  // no coefficients), and every shape after restore() of a whole state until the first
  // advance().
  const std::vector<Cell>& cells() const { return cells_; }
  const CellGrids& grids() const { return *grids_; }  // only with cells: a run of walls alone has none
  const WallCoupling* wall() const { return wall_.get(); }
  // Surface velocity of the last step, stacked over this rank's own cells in that step's
  // products, in owner order (every cell on one rank; nodes x 3).
  const Eigen::MatrixXd& velocity() const { return state_.previous_velocity; }
  const std::vector<double>& initial_volumes() const { return state_.volume0; }
  const std::vector<double>& initial_areas() const { return state_.area0; }
  // Every cell's volume centroid at X^n, in cell order on every rank, each computed by the rank
  // that moved the cell last (cell_centroids.h); empty without cells. Collective.
  std::vector<Eigen::Vector3d> volume_centroids() const;
  // Every cell's measures at X^n and U^n of `s` (this stepper's solve(), before advance()), in
  // cell order on every rank, each computed by its owner in s.owners (cell_measures.h); empty
  // without cells. Collective.
  std::vector<CellMeasures> cell_measures(const FlowSolution& s) const;

  // The whole state, every cell's shape and velocities gathered from the ranks: collective.
  StepperState state() const;
  // This rank's part of the state, its own cells' shapes and velocities (StepperState::part),
  // nothing gathered; the whole state on one rank.
  StepperState held_state() const;
  // Throws std::invalid_argument when the state does not fit (cell count, order, wall size).
  // A rank's part (StepperState::part, read for this rank's block of owned_block) leaves it
  // holding that block's shapes and rows, as if its last step had owned them.
  void restore(const StepperState& s);
  // The state as checkpoint items (StepperState::archive) and the wall's nodes, which a
  // restart checks against the vessel as meshed then; load() throws as restore() does. On
  // several ranks save() is collective: each rank gives its part where the archive takes parts
  // (held_state()), else the whole state (state()); load() reads each rank's part alone.
  void save(StateArchive& a) const;
  void load(StateArchive& a);
  // load() of a state discretised otherwise (another order of the cells or another time
  // step): the shapes are resampled to this stepper's order (zero-padded or truncated
  // coefficients: the same surface, to the truncation) and the velocity history is dropped, so
  // that the first step is forward Euler (11) as a run's first is; the wall's force history
  // stays as the wall solve's guess.
  void load_rediscretised(StateArchive& a);

 private:
  void archive_wall(StateArchive& a) const;
  // How many of U^{n-1}, U^{n-2}, U^{n-3} the state holds (0-3), and the guess of U^n from them
  // (3 U^{n-1} - 3 U^{n-2} + U^{n-3}, or fewer terms): the rows of this rank's cells in
  // history_owners_.
  int velocities_held() const;
  Eigen::MatrixXd extrapolated_velocity() const;
  // Returns the relative volume it restored, |V0 - V| / V0 before the correction.
  double enforce_volume(int c);
  // The rows of this rank's own cells in s.owners of U^n in `s`, in owner order: all of
  // s.velocity as solve() leaves it, or those cells' rows of every cell's (cell order). Throws
  // std::invalid_argument for a solution of another stepper.
  Eigen::MatrixXd owned_velocity(const FlowSolution& s) const;
  // The velocities' history brought to the rows of this rank's cells in `to` (a step's owners)
  // from those of history_owners_: only the rows of cells whose owner changed travel.
  // Collective.
  void migrate_history(const CellOwners& to);
  // The shapes of this rank's cells in `to` brought from the ranks of history_owners_, every
  // other shape released (held_shapes.h). Collective.
  void migrate_shapes(const CellOwners& to);
  // StepReport::discharge_hematocrit for the velocity of `s` (needs its tube velocity) on the
  // current shapes `own` of this rank's cells in s.owners, in owner order. Collective.
  double discharge_hematocrit(const FlowSolution& s, const std::vector<SHSurface>& own) const;
  // X^{n+1}, collision removal and the volume constraint (advance() with cells).
  void move_cells(const FlowSolution& s, StepReport& report);
  int points_per_cell() const { return grids_ ? static_cast<int>(grids_->n_grid->grid().size()) : 0; }

  std::vector<Cell> cells_;
  std::shared_ptr<const CellGrids> grids_;
  CellStepperOptions options_;
  std::unique_ptr<WallCoupling> wall_;
  std::unique_ptr<WallDistance> wall_distance_;  // collision removal against the wall; min_wall_gap
  std::optional<TubeFlowMeter> tube_meter_;      // with options_.tube
  std::unique_ptr<SectionFluxMeter> section_meter_;  // with options_.flux_sections
  // The largest grid array of the step's products, the cells' and the wall's
  // (work_array_pool.h): kept from one product to the next while solve() runs its solves,
  // freed before it returns.
  std::shared_ptr<WorkArrayPool> work_arrays_ = std::make_shared<WorkArrayPool>();
  std::unique_ptr<SpmeGridCache> grid_cache_ = std::make_unique<SpmeGridCache>(work_arrays_);  // the cells' SPME grids
  // The velocities in it are the rows of this rank's cells in history_owners_ (in its order),
  // absent ones 0 x 0; state() gathers them. Its shapes are empty: they are held once, in
  // cells_, and state() copies them.
  StepperState state_;
  // The owners whose cells' rows of the velocities' history each rank holds: the last step's
  // in the products (cell_owners.h), so that the next step brings only the rows of the cells
  // whose owner changed; owned_block's blocks after construction and restore().
  CellOwners history_owners_;
};

}  // namespace rbcflow
