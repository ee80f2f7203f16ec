#pragma once
// A red cell folded face-on into a narrow tube: the start of the parachute that red cells take
// in capillaries (paper section 11.2, fig. 12). The biconcave disc (symmetry axis z, centroid at
// the origin) is mapped onto a parachute of the given outer radius: a blunt nose towards +z, a
// cylindrical side, a rounded trailing rim of thickness 2 w and a dimple in the rear.
//
// The map keeps the cell's area and volume, which the red cell's membrane (dilatation modulus
// 200 against shear modulus 12.4) and incompressible interior demand: the parachute's length
// and dimple depth are solved for them. A squeeze (s, s, 1/s^2) of the disc to the tube's radius
// compresses the faces' area by s^2 instead (0.33 in the D = 1.75 tube), and the membrane then
// pushes its rim out against the wall.
//
// Points go by equal area along the meridian: a point of the disc whose surface beyond it,
// counted from the top face's centre over the rim to the bottom face's centre, is the fraction
// f of the area goes to the parachute's meridian where the same fraction f is reached from the
// nose; its angle about z is kept. The top face becomes the nose and side, the bottom face the
// dimple, and each ring of the membrane keeps its area (stretched along the meridian where it
// is shortened around the axis: shear, which the membrane bears easily).
#include "geometry/surface/sh_surface.h"

namespace rbcflow {

struct ParachuteFold {
  SHSurface surface;  // the folded cell, same order, nose towards +z
  double radius = 0;  // the largest distance from the z axis
  double length = 0;  // extent along z
  double dimple = 0;  // depth of the rear dimple below the rim
};

// `cell`: a disc symmetric about z and about z = 0, centroid at the origin; `radius` (> 0) the
// parachute's outer radius. Throws std::runtime_error where no parachute of that radius has the
// cell's area and volume: the radius too large (the cell would not need folding) or too small.
ParachuteFold fold_into_parachute(const SHSurface& cell, double radius);

}  // namespace rbcflow
