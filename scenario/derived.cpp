#include "scenario/derived.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/surface/reference_shapes.h"

namespace rbcflow {
namespace {

constexpr double kRbcArea = 16.8;  // section 7: the estimated red-cell area used in (37)

}  // namespace

ReferenceCell reference_cell(const CaseCells& cells) {
  if (cells.shape == CellShape::rbc) return {kRbcArea, 4.0 * std::numbers::pi / 3.0};
  const SHSurface s = cells.shape == CellShape::sphere
                          ? make_sphere(cells.order)
                          : make_ellipsoid(cells.order, Eigen::Vector3d(cells.semi_axes[0], cells.semi_axes[1],
                                                                        cells.semi_axes[2]));
  const SurfaceGeometry g = s.geometry(SHTransform::gauss(cells.order));
  return {surface_area(g), enclosed_volume(g)};
}

double effective_spacing(const CaseCells& cells) {
  return std::sqrt(reference_cell(cells).area) / cells.order;
}

double time_step_limit(const CaseCells& cells) {
  const double h = effective_spacing(cells);
  const CaseMembrane& m = cells.membrane;
  // The neo-Hookean membrane resists area change with K_S = 3 E_S: its stiffest in-plane mode.
  const double in_plane = m.law == MembraneLawKind::neo_hookean ? 3.0 * m.shear_modulus : m.dilatation_modulus;
  double limit = 2.5 * std::pow(h, 1.2) / in_plane;  // (37)
  if (m.bending_modulus > 0) limit = std::min(limit, 0.19 * std::pow(h, 3.2) / m.bending_modulus);
  return limit;
}

double time_step(const Case& c) {
  if (c.time.dt) return *c.time.dt;
  if (!c.cells) return c.time.end;
  return std::min(c.time.end, c.time.dt_safety * time_step_limit(*c.cells));
}

int flow_axis(const Case& c) {
  if (c.vessel) return c.vessel->axis;
  if (c.domain.kind == DomainKind::free) return c.domain.background_flow.kind == FlowKind::none ? 2 : 0;
  for (const auto& v : {c.domain.mean_velocity, c.domain.pressure_gradient,
                        c.cells ? std::optional<Vec3>(c.cells->body_force) : std::nullopt}) {
    if (!v) continue;
    const Vec3 a{std::abs((*v)[0]), std::abs((*v)[1]), std::abs((*v)[2])};
    const int k = static_cast<int>(std::max_element(a.begin(), a.end()) - a.begin());
    if (a[k] > 0) return k;
  }
  return 2;
}

double flow_period(const Case& c) {
  return c.domain.kind == DomainKind::periodic ? c.domain.box[flow_axis(c)] : 0.0;
}

}  // namespace rbcflow
