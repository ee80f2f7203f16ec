#include "scenario/vessel.h"

#include <stdexcept>

#include "geometry/vessel/network.h"
#include "geometry/vessel/vessel.h"
#include "geometry/vessel/vessel_branches.h"

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

ConstrictionSpec constriction_spec(const Case& c) {
  ConstrictionSpec s;
  s.tube = tube_spec(c);
  s.depth = c.vessel->depth;
  s.width = c.vessel->width;
  s.centre = c.vessel->center;
  return s;
}

BifurcationSpec bifurcation_spec(const Case& c) {
  BifurcationSpec s;
  s.tube = tube_spec(c);
  s.daughter_diameters = c.vessel->daughter_diameters;
  s.angle_deg = c.vessel->angle_deg;
  s.centre = c.vessel->center;
  s.fillet_radius = c.vessel->fillet_radius;
  return s;
}

NetworkSpec network_spec(const Case& c) {
  NetworkSpec s;
  for (const CaseSegment& g : c.vessel->segments) s.segments.push_back({to_eigen(g.from), to_eigen(g.to), g.diameter});
  s.axis = c.vessel->axis;
  s.box = to_eigen(c.domain.box);
  s.element_size = c.vessel->element_size;
  s.fillet_radius = c.vessel->fillet_radius;
  return s;
}

VesselMesh build(const Case& c) {
  const CaseVessel& v = *c.vessel;
  switch (v.kind) {
    case VesselKind::tube: return tube(tube_spec(c));
    case VesselKind::constriction: return constriction(constriction_spec(c));
    case VesselKind::bifurcation: return bifurcation(bifurcation_spec(c));
    case VesselKind::file: {
      VesselFileSpec s;
      s.path = v.path.string();
      s.scale = v.scale;
      s.axis = v.axis;
      s.box = to_eigen(c.domain.box);
      s.element_size = v.element_size;
      return vessel_file(s);
    }
    case VesselKind::network: return network(network_spec(c));
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

std::vector<VesselBranch> vessel_branches(const Case& c) {
  if (!c.vessel) return {};
  switch (c.vessel->kind) {
    case VesselKind::tube: return tube_branches(tube_spec(c));
    case VesselKind::constriction: return constriction_branches(constriction_spec(c));
    case VesselKind::bifurcation: return bifurcation_branches(bifurcation_spec(c));
    case VesselKind::network: return network_branches(network_spec(c));
    case VesselKind::file: return {};
  }
  return {};
}

}  // namespace rbcflow
