#pragma once
// What a run writes, from the stepper's state and the flow just solved: the surfaces of a
// frame (cells with velocity, force, tension, J_S; the wall with its traction), the rows of
// cells.csv and diagnostics.csv, and where checkpoints and renders go (docs/case-format.md,
// "Output directory").
#include <filesystem>
#include <string>
#include <vector>

#include "io/case.h"
#include "io/csv.h"
#include "io/render.h"
#include "io/surface.h"
#include "libsolver/stepper/cell_stepper.h"
#include "scenario/scenario.h"

namespace rbcflow {

// The cells (merged, with a `cell` index) and the wall of the state X^n with the flow s
// solved there: the cells `begin` .. `end` - 1 (among `cells`, CellStepper::cells_for_output),
// their points and triangles numbered as in the whole frame's "cells" surface (cell c's points
// from c x cell_frame_points on), so that the ranks can write their parts of it.
std::vector<Surface> frame_surfaces(const CellStepper& stepper, const FlowSolution& s, const CellsForOutput& cells,
                                    int begin, int end);
// A cell's points and triangles in a frame (the grid's points and the two poles).
long cell_frame_points(const CellStepper& stepper);
long cell_frame_triangles(const CellStepper& stepper);

// One row per cell, each cell's measured by its owner in s.owners (cell_measures.h) and
// gathered; `flow_axis` for the inclination (signed in the x-z plane of a shear flow along x,
// otherwise the angle to the axis in [0, pi/2]). Collective: every rank calls it.
std::vector<CellRow> cell_rows(const CellStepper& stepper, const FlowSolution& s, int flow_axis, bool shear);

// The renders a case asks for ([output] render_*; the flow axis and period for the view and the
// wrapping of cells); no field for a case without cells.
RenderOptions render_options(const Case& c);

// The row of diagnostics.csv after a step: the report of advance(), (45)-(46) in a straight
// tube, the tube hematocrit with a vessel, `seconds` the step's wall-clock time.
DiagnosticsRow diagnostics_row(const CellStepper& stepper, const StepReport& r, const Scenario& s, double seconds);

// checkpoints/step_NNNNNNNN.h5 and renders/step_NNNNNNNN.png under the output directory.
std::filesystem::path checkpoint_path(const std::filesystem::path& dir, long step);
std::filesystem::path render_path(const std::filesystem::path& dir, long step);

}  // namespace rbcflow
