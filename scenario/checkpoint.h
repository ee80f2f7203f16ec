#pragma once
// A run's checkpoint: the stepper's own items (CellStepper::save, StepperState::archive) in an
// HDF5 file (io/checkpoint.h) under the case's fingerprint, with the version of their layout,
// `state_version`. Version 1 (no such item) and 2 read alike; 2 no longer carries the cells'
// reference shapes, which nothing read, and adds `case`, the case as run (case.toml's text),
// so that a checkpoint alone can be continued (case_of_checkpoint). Version 3 may hold the
// cells' velocity history in the order of `cells/velocity_order` (written by several ranks,
// each its own cells' rows), which a reader of version 2 would take for cell order.
#include <filesystem>
#include <string>
#include <vector>

#include "io/case.h"
#include "io/checkpoint.h"
#include "libsolver/parallel/communicator.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow {

inline constexpr long kCheckpointStateVersion = 3;

// Written atomically (io/checkpoint.h); throws std::runtime_error naming the file when it
// cannot be. Every rank of a run calls it: with parallel HDF5 the ranks write the file
// together, each its own cells' shapes and velocities (nothing gathered: CellStepper::save)
// and its block of the rows of the rest, else rank 0 writes it alone from the state gathered.
void write_checkpoint(const CellStepper& stepper, const Case& c, const std::filesystem::path& file,
                      const Communicator& ranks = {});
// Reads a checkpoint of this case into the stepper; throws CheckpointError (exit 2) naming the
// file when it does not fit the case or has a format this build does not read. The case may
// discretise the checkpoint's run otherwise (rediscretised_keys): its cells are then resampled
// to the case's order and the velocity history starts afresh (CellStepper::load_rediscretised).
void read_checkpoint(CellStepper& stepper, const Case& c, const std::filesystem::path& file);
// A restart continues the same physics and may change only its discretisation: the cells'
// order and de-aliasing (cells.order, cells.dealias) and the time step (time.dt,
// time.dt_safety); and the contact repulsion (time.contact_range, time.contact_strength), the
// model of what happens below the resolved gaps, so that a run whose cells jam can go on with
// one. `c` with those keys set to the checkpoint's run's (the case it holds, or its run's
// case.toml); `c` itself where the checkpoint's case cannot be read, so that the fingerprint
// then decides alone. Throws nothing of its own.
Case as_run_of_checkpoint(const Case& c, const std::filesystem::path& file);
// The rediscretised keys whose values differ between `c` and `run`, as "key old -> new"; empty
// for a restart of the same discretisation.
std::vector<std::string> rediscretised_keys(const Case& run, const Case& c);
// The contact repulsion's keys whose values differ between `c` and `run`, as "key old -> new"
// (the state, its history included, continues exactly: only the forces from the next step on
// differ).
std::vector<std::string> contact_keys(const Case& run, const Case& c);
// The case a checkpoint was written for: its `case` item, or, for a checkpoint without one,
// the case.toml of the run that wrote it (RUN/checkpoints/step_N.h5). Throws CheckpointError
// naming the file when neither is there.
Case case_of_checkpoint(const std::filesystem::path& file);

}  // namespace rbcflow
