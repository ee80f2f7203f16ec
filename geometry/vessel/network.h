#pragma once
// Vessel networks from straight segments (case `[vessel] kind = "network"`): a cylinder per
// segment, joined at shared end points (junctions), periodic through the two box faces along
// the axis like the tube. network_layout validates the description and finds its junctions
// without gmsh; network() meshes it (vessel.h's conventions: normals into the lumen, the seam
// nodes merged).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

struct NetworkSegment {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();  // box coordinates
  double diameter = 0.0;
};

struct NetworkSpec {
  std::vector<NetworkSegment> segments;
  int axis = 2;
  Eigen::Vector3d box = Eigen::Vector3d::Zero();
  double element_size = 0.0;
  double fillet_radius = 0.0;  // rounds the creases at the junctions (0: sharp); below every segment's radius
};

// A point where segment ends meet. An end on the box face at the axis coordinate box[axis] is
// the same point as its periodic partner on the face at 0, and is stored there.
struct NetworkNode {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  std::vector<int> segments;  // the segments with an end here (twice for none)
  bool on_face = false;       // on the box faces along the axis: the periodic seam
  // The junction sphere: the widest radius meeting here; 0 on the seam and where two segments
  // of one diameter continue each other in a straight line (their cylinders meet flush).
  double sphere_radius = 0.0;
};

struct NetworkLayout {
  std::vector<NetworkNode> nodes;
  std::vector<std::array<int, 2>> ends;  // per segment: the nodes of `from` and `to`
};

// Throws std::invalid_argument naming the segment (0-based, in the order given) for: a bad
// axis, box or element size; a segment of zero length or a diameter not above twice the element
// size; a segment that leaves the box sideways or past the faces along the axis; an open end
// (an end shared by no other segment that is not on a box face, or one on a face whose periodic
// partner is missing, has another diameter or direction); two segments that overlap (not
// sharing an end and closer than the sum of their radii, periodic images included; or sharing
// one at too small an angle to part before either ends); a network in more than one piece.
NetworkLayout network_layout(const NetworkSpec& spec);

// The lumen of the segments' cylinders fused with a sphere of the widest meeting radius at
// every junction (each cylinder meets the sphere of its own radius tangentially, so a straight
// run through a junction stays smooth), cut flat at the box faces along the axis, meshed with
// triangles of the target size; the end curves periodic as for the tube. fillet_radius > 0
// rounds the creases where segments meet the junction spheres and each other (crease_fillet.h)
// before meshing. Throws as
// network_layout does, and std::runtime_error when OpenCASCADE cannot fuse or mesh it.
VesselMesh network(const NetworkSpec& spec);

}  // namespace rbcflow
