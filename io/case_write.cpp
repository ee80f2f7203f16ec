// The case as run (every default filled in) as TOML, its fingerprint, and the small helpers
// of case.h that need no TOML parser.
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "io/atomic_file.h"
#include "io/case.h"

namespace rbcflow {
namespace {

namespace fs = std::filesystem;

// Shortest text that reads back as the same double, always with a '.' or an exponent so that
// TOML reads a float.
std::string real(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".en") == std::string::npos) s.append(".0");
  return s;
}

std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (const unsigned char ch : s) {
    if (ch == '"' || ch == '\\') {
      q.push_back('\\');
      q.push_back(static_cast<char>(ch));
    } else if (ch < 0x20 || ch == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", ch);
      q.append(buf);
    } else {
      q.push_back(static_cast<char>(ch));
    }
  }
  return q + "\"";
}

// "[a, b, c]", built with append (GCC 12 raises a false -Wrestrict on "literal" + string).
std::string list(const std::vector<std::string>& items) {
  std::string s = "[";
  for (const auto& x : items) s.append(s.size() > 1 ? ", " : "").append(x);
  return s.append("]");
}

std::string vec(const Vec3& x) { return list({real(x[0]), real(x[1]), real(x[2])}); }

std::string vec_list(const std::vector<Vec3>& items) {
  std::string s = "[\n";
  for (const Vec3& x : items) s.append("  ").append(vec(x)).append(",\n");
  return s.append("]");
}

class Writer {
 public:
  void table(const std::string& name) { out_ << "\n[" << name << "]\n"; }
  void key(const std::string& k, const std::string& value) { out_ << k << " = " << value << "\n"; }
  void key(const std::string& k, double value) { key(k, real(value)); }
  void key(const std::string& k, int value) { key(k, std::to_string(value)); }
  void key(const std::string& k, bool value) { key(k, std::string(value ? "true" : "false")); }
  void text(const std::string& k, const std::string& value) { key(k, quoted(value)); }
  void comment(const std::string& c) { out_ << "# " << c << "\n"; }
  std::string str() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

void write_domain(Writer& w, const CaseDomain& d) {
  w.table("domain");
  w.text("kind", to_string(d.kind));
  if (d.kind == DomainKind::periodic) {
    w.key("box", vec(d.box));
    if (d.mean_velocity) w.key("mean_velocity", vec(*d.mean_velocity));
    if (d.pressure_gradient) w.key("pressure_gradient", vec(*d.pressure_gradient));
    if (d.tube_velocity) w.key("tube_velocity", *d.tube_velocity);
    if (d.pseudo_shear_rate) w.key("pseudo_shear_rate", *d.pseudo_shear_rate);
  } else {
    std::string flow = "{ kind = ";
    flow.append(quoted(to_string(d.background_flow.kind)));
    if (d.background_flow.kind != FlowKind::none) flow.append(", rate = ").append(real(d.background_flow.rate));
    w.key("background_flow", flow.append(" }"));
  }
  w.key("viscosity_ratio", d.viscosity_ratio);
}

void write_vessel(Writer& w, const CaseVessel& v) {
  w.table("vessel");
  w.text("kind", to_string(v.kind));
  w.text("axis", axis_name(v.axis));
  if (v.kind == VesselKind::file) {
    w.text("path", v.path.string());
    w.key("scale", v.scale);
  } else if (v.kind == VesselKind::network) {
    std::string segments = "[\n";
    for (const CaseSegment& g : v.segments)
      segments.append("  { from = ").append(vec(g.from)).append(", to = ").append(vec(g.to))
          .append(", diameter = ").append(real(g.diameter)).append(" },\n");
    w.key("segments", segments.append("]"));
  } else {
    w.key("diameter", v.diameter);
  }
  w.key("element_size", v.element_size);
  if (v.fillet_radius > 0) w.key("fillet_radius", v.fillet_radius);
  if (v.kind == VesselKind::constriction) {
    w.key("depth", v.depth);
    w.key("width", v.width);
    w.key("center", v.center);
  } else if (v.kind == VesselKind::bifurcation) {
    w.key("daughter_diameters", list({real(v.daughter_diameters[0]), real(v.daughter_diameters[1])}));
    w.key("angle_deg", v.angle_deg);
    w.key("center", v.center);
  }
}

void write_cells(Writer& w, const CaseCells& c) {
  w.table("cells");
  w.text("shape", to_string(c.shape));
  if (c.count) w.key("count", *c.count);
  if (c.hematocrit) w.key("hematocrit", *c.hematocrit);
  w.key("order", c.order);
  w.key("dealias", c.dealias);
  w.key("seed", c.seed);
  w.text("narrow_start", to_string(c.narrow_start));
  if (!c.positions.empty()) w.key("positions", vec_list(c.positions));
  if (!c.orientations.empty()) w.key("orientations", vec_list(c.orientations));
  w.key("body_force", vec(c.body_force));
  if (c.perturbation) {
    std::string p = "{ l = ";
    p.append(std::to_string(c.perturbation->l)).append(", m = ").append(std::to_string(c.perturbation->m));
    p.append(", amplitude = ").append(real(c.perturbation->amplitude)).append(" }");
    w.key("perturbation", p);
  }
  if (c.shape == CellShape::ellipsoid) w.key("semi_axes", vec(c.semi_axes));
  w.table("cells.membrane");
  w.text("law", to_string(c.membrane.law));
  w.key("shear_modulus", c.membrane.shear_modulus);
  if (c.membrane.law != MembraneLawKind::neo_hookean) {
    w.key("dilatation_modulus", c.membrane.dilatation_modulus);
  }
  w.key("bending_modulus", c.membrane.bending_modulus);
}

void write_ewald(Writer& w, const CaseEwald& e) {
  w.table("ewald");
  w.key("tolerance", e.tolerance);
  if (e.alpha) w.key("alpha", *e.alpha);
  if (e.cutoff) w.key("cutoff", *e.cutoff);
  if (e.grid) {
    const auto& g = *e.grid;
    w.key("grid", list({std::to_string(g[0]), std::to_string(g[1]), std::to_string(g[2])}));
  }
  if (e.spline_order) w.key("spline_order", *e.spline_order);
}

void write_time(Writer& w, const CaseTime& t) {
  w.table("time");
  w.key("end", t.end);
  if (t.dt) {
    w.key("dt", *t.dt);
  } else {
    w.text("dt", "auto");
    w.key("dt_safety", t.dt_safety);
  }
  w.text("scheme", to_string(t.scheme));
  w.key("collision_threshold", t.collision_threshold);
  if (t.contact_range > 0) {  // absent when off: a case without it hashes as before the keys existed
    w.key("contact_range", t.contact_range);
    w.key("contact_strength", t.contact_strength);
  }
  w.key("volume_constraint", t.volume_constraint);
}

void write_output(Writer& w, const CaseOutput& o) {
  w.table("output");
  w.text("dir", o.dir.string());
  w.key("every", o.every);
  std::vector<std::string> formats;
  if (o.xdmf) formats.push_back(quoted("xdmf"));
  if (o.vtk) formats.push_back(quoted("vtk"));
  w.key("formats", list(formats));
  w.key("render", o.render);
  w.key("render_every", o.render_every);
  w.text("render_field", o.render_field);
  w.text("render_view", to_string(o.render_view));
  w.key("render_size", list({std::to_string(o.render_size[0]), std::to_string(o.render_size[1])}));
  w.key("checkpoint_every", o.checkpoint_every);
}

std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h = 14695981039346656037ull) {
  for (const unsigned char b : bytes) {
    h ^= b;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

int CaseSource::line(const std::string& key) const {
  for (std::string k = key;;) {
    if (const auto it = lines.find(k); it != lines.end()) return it->second;
    const auto dot = k.rfind('.');
    if (dot == std::string::npos) return 0;
    k.resize(dot);
  }
}

bool Case::operator==(const Case& o) const {
  return title == o.title && domain == o.domain && vessel == o.vessel && cells == o.cells &&
         ewald == o.ewald && solver == o.solver && time == o.time && output == o.output && units == o.units;
}

CaseError case_error(const Case& c, const std::string& key, const std::string& message) {
  std::string m = c.source.file.string();
  if (const int line = c.source.line(key); line > 0) m.append(":").append(std::to_string(line));
  m.append(": ").append(key).append(": ").append(message);
  return CaseError(m);
}

std::string case_toml(const Case& c) {
  Writer w;
  w.comment("The case as run by rbcflow: every default filled in (docs/case-format.md).");
  w.text("title", c.title);
  write_domain(w, c.domain);
  if (c.vessel) write_vessel(w, *c.vessel);
  if (c.cells) write_cells(w, *c.cells);
  write_ewald(w, c.ewald);
  w.table("solver");
  w.key("gmres_tolerance", c.solver.gmres_tolerance);
  w.key("max_iterations", c.solver.max_iterations);
  if (c.solver.patch_radial_points) w.key("patch_radial_points", *c.solver.patch_radial_points);
  if (c.solver.memory_gib) w.key("memory_gib", *c.solver.memory_gib);
  if (c.solver.wall_preconditioner_block_nodes != CaseSolver{}.wall_preconditioner_block_nodes)
    w.key("wall_preconditioner_block_nodes", c.solver.wall_preconditioner_block_nodes);
  write_time(w, c.time);
  write_output(w, c.output);
  w.table("units");
  w.key("length_um", c.units.length_um);
  w.key("rate_per_s", c.units.rate_per_s);
  w.key("plasma_viscosity_mpas", c.units.plasma_viscosity_mpas);
  return w.str();
}

void write_case_toml(const Case& c, const fs::path& file) {
  const std::string text = case_toml(c);
  write_atomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + file.string());
  });
}

std::string case_fingerprint(const Case& c) {
  Case physics = c;
  physics.title.clear();
  physics.output = CaseOutput{};
  physics.time.end = 1.0;
  // The preconditioner changes a solve's iterations, not its solution (to the GMRES tolerance):
  // a checkpoint restarts with any blocks.
  physics.solver.wall_preconditioner_block_nodes = CaseSolver{}.wall_preconditioner_block_nodes;
  std::string mesh_bytes;
  if (physics.vessel && physics.vessel->kind == VesselKind::file) {
    // The mesh file by its name and content, not by the folder it lies in.
    std::ifstream in(physics.vessel->path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    mesh_bytes = bytes.str();
    physics.vessel->path = physics.vessel->path.filename();
  }
  // The scales of [units] change the physics only through domain.pseudo_shear_rate; a case
  // with the default scales hashes as before [units] existed, so earlier checkpoints still fit.
  std::string text = case_toml(physics);
  if (physics.units == CaseUnits{}) text.erase(text.rfind("\n[units]\n"));
  const std::uint64_t h = fnv1a(mesh_bytes, fnv1a(text));
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string to_string(DomainKind k) { return k == DomainKind::periodic ? "periodic" : "free"; }
std::string to_string(FlowKind k) {
  return k == FlowKind::none ? "none" : k == FlowKind::shear ? "shear" : "extensional";
}
std::string to_string(VesselKind k) {
  switch (k) {
    case VesselKind::tube: return "tube";
    case VesselKind::constriction: return "constriction";
    case VesselKind::bifurcation: return "bifurcation";
    case VesselKind::file: return "file";
    case VesselKind::network: return "network";
  }
  return "";
}
std::string to_string(CellShape s) {
  return s == CellShape::rbc ? "rbc" : s == CellShape::sphere ? "sphere" : "ellipsoid";
}
std::string to_string(NarrowStartKind s) { return s == NarrowStartKind::parachute ? "parachute" : "stretched"; }
std::string to_string(MembraneLawKind l) {
  return l == MembraneLawKind::skalak ? "skalak" : l == MembraneLawKind::neo_hookean ? "neo-hookean" : "hookean";
}
std::string to_string(TimeSchemeKind s) { return s == TimeSchemeKind::euler ? "euler" : "ab2"; }
std::string to_string(RenderView v) {
  return v == RenderView::side ? "side" : v == RenderView::end ? "end" : "iso";
}

}  // namespace rbcflow
