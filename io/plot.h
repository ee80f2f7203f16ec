#pragma once
// The plot of a run as PNG (VTK charts): effective viscosity (when there is a tube) and the
// mean pressure gradient against time, from diagnostics.csv. Needs an X display like
// io/render.h.
#include <filesystem>

namespace rbcflow {

// Throws std::runtime_error naming the file when diagnostics.csv is missing, has no rows, or
// the PNG cannot be written (or there is no display).
void plot_diagnostics(const std::filesystem::path& diagnostics_csv, const std::filesystem::path& png,
                      int width = 1000, int height = 700);

}  // namespace rbcflow
