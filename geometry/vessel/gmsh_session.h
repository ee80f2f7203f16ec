#pragma once
// One gmsh session (initialize ... finalize) that restores the OpenMP thread count gmsh resets,
// keeps the terminal quiet; gmsh_last_error for messages; and the mesh it made. Internal to rbcflow_vessel.
#include <string>

#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  int threads_;
};

// gmsh's last error message (gmsh throws non-standard exceptions: catch (...) and ask here).
std::string gmsh_last_error();

// The triangles of the current gmsh model's mesh (all surfaces), with the nodes they use.
TriangleMesh gmsh_triangles();

}  // namespace rbcflow
