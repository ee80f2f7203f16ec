#include "scenario/vessel.h"

#include <stdexcept>

#include "geometry/vessel/network.h"
#include "geometry/vessel/vessel.h"

namespace rbcflow {
namespace {

Eigen::Vector3d to_eigen(const Vec3& v) { return {v[0], v[1], v[2]}; }

TubeSpec tube_spec(const Case& c) {
  TubeSpec t;
  t.diameter = c.vessel->diameter;
  t.axis = c.vessel->axis;
  t.box = to_eigen(c.domain.box);
  t.element_size = c.vessel->element_size;
  return t;
}

VesselMesh build(const Case& c) {
  const CaseVessel& v = *c.vessel;
  switch (v.kind) {
    case VesselKind::tube: return tube(tube_spec(c));
    case VesselKind::constriction: {
      ConstrictionSpec s;
      s.tube = tube_spec(c);
      s.depth = v.depth;
      s.width = v.width;
      s.centre = v.center;
      return constriction(s);
    }
    case VesselKind::bifurcation: {
      BifurcationSpec s;
      s.tube = tube_spec(c);
      s.daughter_diameters = v.daughter_diameters;
      s.angle_deg = v.angle_deg;
      s.centre = v.center;
      return bifurcation(s);
    }
    case VesselKind::file: {
      VesselFileSpec s;
      s.path = v.path.string();
      s.scale = v.scale;
      s.axis = v.axis;
      s.box = to_eigen(c.domain.box);
      s.element_size = v.element_size;
      return vessel_file(s);
    }
    case VesselKind::network: {
      NetworkSpec s;
      for (const CaseSegment& g : v.segments) s.segments.push_back({to_eigen(g.from), to_eigen(g.to), g.diameter});
      s.axis = v.axis;
      s.box = to_eigen(c.domain.box);
      s.element_size = v.element_size;
      return network(s);
    }
  }
  throw std::logic_error("build_vessel: unknown vessel kind");
}

}  // namespace

VesselMesh build_vessel(const Case& c) {
  if (!c.vessel) throw case_error(c, "vessel", "the case has no [vessel] table: there is no wall to mesh");
  try {
    return build(c);
  } catch (const std::exception& e) {
    const VesselKind kind = c.vessel->kind;
    throw case_error(c, kind == VesselKind::file ? "vessel.path" : kind == VesselKind::network ? "vessel.segments" : "vessel",
                     e.what());
  }
}

}  // namespace rbcflow
