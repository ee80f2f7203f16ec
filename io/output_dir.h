#pragma once
// The output directory of a run (docs/case-format.md, "Output directory"): case.toml,
// diagnostics.csv, cells.csv, rbcflow.xdmf + rbcflow.h5, rbcflow.pvd + vtk/, renders/,
// checkpoints/ and diagnostics.png.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/case.h"

namespace rbcflow {

// Throws CaseError naming output.dir when `dir` exists but is not a directory, or cannot be
// created or written (its nearest existing ancestor is not a writable directory). Creates
// nothing.
void check_output_dir(const Case& c, const std::filesystem::path& dir);

// Whether `dir` holds any file of a run (an empty vtk/, renders/ or checkpoints/ folder does
// not count).
bool holds_run(const std::filesystem::path& dir);
// The run's files and folders that `dir` holds, by name (for messages).
std::vector<std::string> run_files(const std::filesystem::path& dir);
// Removes a run's files and folders from `dir`, nothing else; throws std::runtime_error naming
// what cannot be removed.
void clear_run(const std::filesystem::path& dir);

// Creates `dir` and its vtk/, renders/ and checkpoints/ folders; throws std::runtime_error
// naming the folder that cannot be created.
void prepare_output_dir(const std::filesystem::path& dir);

// RUN for a checkpoint RUN/checkpoints/step_N.h5 (the run that wrote it); nothing for a
// checkpoint elsewhere.
std::optional<std::filesystem::path> run_of_checkpoint(const std::filesystem::path& checkpoint);
// Whether the checkpoint was written by the run in `dir` (a restart in place).
bool restarts_in_place(const std::filesystem::path& checkpoint, const std::filesystem::path& dir);

// A restart into another directory than that of the run which wrote the checkpoint
// (RUN/checkpoints/step_N.h5): copies RUN's diagnostics.csv and cells.csv into `dir` where `dir`
// has none, so that the restarted run's tables begin at step 1 as after a restart in place (the
// rows after the checkpoint's step are dropped when the run opens them). RUN is left untouched.
// Returns RUN when something was copied; nothing when the checkpoint is not in a run's
// checkpoints/ folder, RUN is `dir`, or `dir` already has both tables.
std::optional<std::filesystem::path> carry_tables_from_checkpoint_run(const std::filesystem::path& checkpoint,
                                                                      const std::filesystem::path& dir);

}  // namespace rbcflow
