#pragma once
// Rounding a fused lumen's creases (internal to rbcflow_vessel; call inside a GmshSession, in
// the frame of vessel_periodic.h with the vessel axis along z).
#include <string>
#include <utility>

namespace rbcflow {

// Rounds every crease of the OCC volume `lumen` (a curve between two of its faces meeting at
// more than 5 degrees, but the curves in the box faces z = 0 and z = length, where the periodic
// wall is cut) with OpenCASCADE's fillet of `radius`, synchronizes the model and returns the new
// volume. Seams of revolved or piped faces (tangent faces) are left alone. Throws
// std::runtime_error naming `what` and the radius when OpenCASCADE cannot fit the fillet.
std::pair<int, int> round_creases(std::pair<int, int> lumen, double radius, double length, const std::string& what);

}  // namespace rbcflow
