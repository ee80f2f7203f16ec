#pragma once
// A case: everything a run needs, read from a TOML case file. The keys, defaults and ranges
// are documented in docs/case-format.md. Units as in
// section 6 of the paper: lengths in the equivalent cell radius a, time in 1/k*, viscosity in
// plasma viscosity. The periodic box spans [0, L1) x [0, L2) x [0, L3); a vessel's axis runs
// through the centre of the box's cross-section.
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/input_error.h"

namespace rbcflow {

using Vec3 = std::array<double, 3>;

enum class DomainKind { periodic, free };
enum class FlowKind { none, shear, extensional };
enum class VesselKind { tube, constriction, bifurcation, file, network };
enum class CellShape { rbc, sphere, ellipsoid };
// How cells start in a tube narrower than the cell: stretched edge-on, or folded face-on into
// parachutes (geometry/contact/cell_placement.h).
enum class NarrowStartKind { stretched, parachute };
enum class MembraneLawKind { skalak, neo_hookean, hookean };
enum class TimeSchemeKind { euler, ab2 };
enum class RenderView { side, end, iso };

// The imposed linear flow of a free domain: shear u = rate z e_x; extensional (planar)
// u = rate (x e_x - y e_y); none: a quiescent fluid.
struct BackgroundFlow {
  FlowKind kind = FlowKind::none;
  double rate = 1.0;
  bool operator==(const BackgroundFlow&) const = default;
};

struct CaseDomain {
  DomainKind kind = DomainKind::periodic;
  Vec3 box{};  // periodic only
  // A periodic domain has exactly one of these: <u> of (6), or <grad p> with (6)-(8) solved
  // for <u>, or the tube velocity.
  std::optional<Vec3> mean_velocity;
  std::optional<Vec3> pressure_gradient;
  // Or the mean velocity U inside a tube or constriction, along its axis, held every step
  // (libsolver/stepper/tube_drive.h); or U / D in 1/s (the pseudo-shear rate, physical: [units]).
  std::optional<double> tube_velocity;
  std::optional<double> pseudo_shear_rate;
  double viscosity_ratio = 5.0;     // lambda
  BackgroundFlow background_flow;   // free only
  bool operator==(const CaseDomain&) const = default;
};

// A straight segment of a network vessel (box coordinates).
struct CaseSegment {
  Vec3 from{}, to{};
  double diameter = 0;
  bool operator==(const CaseSegment&) const = default;
};

struct CaseVessel {
  VesselKind kind = VesselKind::tube;
  double diameter = 0;  // tube; constriction away from the neck; bifurcation: the parent
  int axis = 2;         // 0, 1, 2 = x, y, z: the vessel is periodic along this box axis
  double element_size = 0.25;
  // constriction: d(s) = diameter - depth exp(-width (s - center)^2), s along the axis.
  // bifurcation: the branching point is at s = center.
  double depth = 0, width = 0, center = 0;
  // bifurcation: two daughters at +-angle_deg / 2 to the axis.
  std::array<double, 2> daughter_diameters{};
  double angle_deg = 0;
  // bifurcation, network: the edges where vessels meet rounded with this radius (0: sharp).
  double fillet_radius = 0;
  // file: a gmsh .msh, .stl or .step surface (absolute path, resolved against the case file's
  // folder); its coordinates are multiplied by `scale`.
  std::filesystem::path path;
  double scale = 1.0;
  // network: straight segments; shared end points are junctions (geometry/vessel/network.h).
  std::vector<CaseSegment> segments;
  bool operator==(const CaseVessel&) const = default;
};

struct CaseMembrane {
  MembraneLawKind law = MembraneLawKind::skalak;
  double shear_modulus = 12.4;        // Es, (35)
  double dilatation_modulus = 200.0;  // Ed
  double bending_modulus = 0.0669;    // Eb, (35)
  bool operator==(const CaseMembrane&) const = default;
};

// A bending eigenmode of degree l added at t = 0 (section 9); m < 0 selects sin(|m| phi).
struct CasePerturbation {
  int l = 2;
  int m = 0;
  double amplitude = 1e-4;
  bool operator==(const CasePerturbation&) const = default;
};

struct CaseCells {
  CellShape shape = CellShape::rbc;
  // Exactly one of count and hematocrit (the tube hematocrit; needs a vessel).
  std::optional<int> count;
  std::optional<double> hematocrit;
  int order = 16;   // N: degrees n < N; grid N x 2N
  int dealias = 3;  // M / N; membrane forces on the M x 2M grid
  int seed = 1;     // random placement and orientation
  NarrowStartKind narrow_start = NarrowStartKind::stretched;
  std::vector<Vec3> positions;     // empty: placed at random
  std::vector<Vec3> orientations;  // symmetry axes; empty: random
  Vec3 body_force{};               // net external force on each cell
  std::optional<CasePerturbation> perturbation;
  Vec3 semi_axes{0.8, 0.9, 1.0};   // ellipsoid only
  CaseMembrane membrane;
  bool operator==(const CaseCells&) const = default;
};

// Ewald summation: the solver chooses alpha, cutoff, grid and spline order from the
// tolerance; any of them may be set by hand.
struct CaseEwald {
  double tolerance = 1e-6;
  std::optional<double> alpha;
  std::optional<double> cutoff;
  std::optional<std::array<int, 3>> grid;
  std::optional<int> spline_order;
  bool operator==(const CaseEwald&) const = default;
};

struct CaseSolver {
  double gmres_tolerance = 1e-6;
  int max_iterations = 100;
  // Radial Gauss points of the singular and nearly-singular patches (section 5.4); the
  // angular points are twice as many. Empty: libsolver's default, max(8, ceil(3 sqrt(N))).
  std::optional<int> patch_radial_points;
  // The memory the run may use, GiB; empty: the machine's physical memory. rbcflow check and
  // run refuse a case whose estimate exceeds it (scenario/memory_budget.h).
  std::optional<double> memory_gib;
  // The wall nodes of a block of the wall solve's block-Jacobi preconditioner
  // (libsolver/wall/wall_preconditioner.h); a wall of at most this many is one block.
  int wall_preconditioner_block_nodes = 500;
  bool operator==(const CaseSolver&) const = default;
};

struct CaseTime {
  double end = 10.0;
  std::optional<double> dt;  // empty: "auto", dt_safety times the limit (37)
  double dt_safety = 0.5;
  TimeSchemeKind scheme = TimeSchemeKind::euler;
  double collision_threshold = 0.02;  // h_s; 0 disables collision removal
  // The contact repulsion between membranes and from the wall (libsolver/stepper/contact_force.h):
  // its range delta (0: none) and strength kappa, the traction at delta / 2 times 2.
  double contact_range = 0.0;
  double contact_strength = 0.0;
  bool volume_constraint = true;
  bool operator==(const CaseTime&) const = default;
};

struct CaseOutput {
  std::filesystem::path dir;  // relative to the working directory; default out/<case name>
  int every = 100;            // steps between ParaView frames
  bool xdmf = true;           // formats = ["xdmf", "vtk"]
  bool vtk = true;
  bool render = true;
  int render_every = 0;  // 0: the last step only
  std::string render_field = "tension";  // a point field of the cells, or "none"
  RenderView render_view = RenderView::iso;
  std::array<int, 2> render_size{1280, 720};
  int checkpoint_every = 1000;  // 0: none
  bool operator==(const CaseOutput&) const = default;
};

// The physical scales of section 6, for reports in physical units and for inputs given in
// them (domain.pseudo_shear_rate); the solver works in the non-dimensional values.
struct CaseUnits {
  double length_um = 2.82;             // a*, the equivalent cell radius
  double rate_per_s = 100.0;           // k*: one time unit is 1 / k*
  double plasma_viscosity_mpas = 1.2;  // mu*, the suspending fluid's viscosity
  bool operator==(const CaseUnits&) const = default;
};

// Where each key came from, for messages that name the file and line.
struct CaseSource {
  std::filesystem::path file;
  std::map<std::string, int> lines;  // dotted key ("cells.order", "cells") -> line
  // The line of `key`, else of the nearest enclosing table given, else 0.
  int line(const std::string& key) const;
};

struct Case {
  std::string title;
  CaseDomain domain;
  std::optional<CaseVessel> vessel;
  std::optional<CaseCells> cells;
  CaseEwald ewald;
  CaseSolver solver;
  CaseTime time;
  CaseOutput output;
  CaseUnits units;
  CaseSource source;  // not part of the comparison

  bool operator==(const Case& other) const;
};

// Reads and validates a case file. Throws CaseError (file, line, key, reason, allowed range)
// for malformed TOML, unknown keys, wrong types and out-of-range or inconsistent values.
Case read_case(const std::filesystem::path& file);
// The same from text; `file` names it in messages and resolves relative paths.
Case parse_case(const std::string& text, const std::filesystem::path& file);

// The case as TOML with every default filled in; read_case of it gives an equal Case.
std::string case_toml(const Case& c);
// Writes case_toml(c) atomically.
void write_case_toml(const Case& c, const std::filesystem::path& file);

// 16 hex digits identifying the physics of a case: everything but title, output and time.end
// (a restart may run longer or write elsewhere). Checkpoints carry it.
std::string case_fingerprint(const Case& c);

// "FILE:LINE: key: message" for errors found after parsing (placement, meshing).
CaseError case_error(const Case& c, const std::string& key, const std::string& message);

// Names as written in case files.
std::string to_string(DomainKind k);
std::string to_string(FlowKind k);
std::string to_string(VesselKind k);
std::string to_string(CellShape s);
std::string to_string(NarrowStartKind s);
std::string to_string(MembraneLawKind l);
std::string to_string(TimeSchemeKind s);
std::string to_string(RenderView v);

}  // namespace rbcflow
