#pragma once
// One gmsh session (initialize ... finalize) that restores the OpenMP thread count gmsh resets,
// keeps the terminal quiet and turns gmsh errors into exceptions; and the mesh it made. Internal to rbcflow_vessel.
#include "vessel_mesh.h"

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

// The triangles of the current gmsh model's mesh (all surfaces), with the nodes they use.
TriangleMesh gmsh_triangles();

}  // namespace rbcflow
