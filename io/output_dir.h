#pragma once
// The output directory of a run (CASE_FORMAT.md "Output directory").
#include <filesystem>

#include "io/case.h"

namespace rbcflow {

// Throws CaseError naming output.dir when `dir` exists but is not a directory, or cannot be
// created or written (its nearest existing ancestor is not a writable directory). Creates
// nothing.
void check_output_dir(const Case& c, const std::filesystem::path& dir);

// Creates `dir` and its vtk/, renders/ and checkpoints/ folders; throws std::runtime_error
// naming the folder that cannot be created.
void prepare_output_dir(const std::filesystem::path& dir);

}  // namespace rbcflow
