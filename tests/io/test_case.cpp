// Case files: every key and default, the round trip through write_case_toml, and bad input
// (each error names the file, the line, the key and the allowed range).
#include "io/case.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

const char* kFull = R"(title = "27 cells"

[domain]
kind = "periodic"
box = [6.6, 6.6, 12.0]
mean_velocity = [0, 0, 5]
viscosity_ratio = 5.0

[vessel]
kind = "tube"
diameter = 6.0
axis = "z"
element_size = 0.25

[cells]
shape = "rbc"
count = 27
order = 16
dealias = 3
seed = 1
body_force = [0, 0, -1]
perturbation = { l = 4, m = 2, amplitude = 1e-4 }

[cells.membrane]
law = "skalak"
shear_modulus = 12.4
dilatation_modulus = 200
bending_modulus = 0.0669

[ewald]
tolerance = 1e-6
alpha = 1.5
cutoff = 3.0
grid = [64, 64, 128]
spline_order = 6

[solver]
gmres_tolerance = 1e-6
max_iterations = 100
patch_radial_points = 24
wall_preconditioner_block_nodes = 2000

[time]
end = 10.0
dt = "auto"
scheme = "euler"
collision_threshold = 0.02
volume_constraint = true

[output]
dir = "out/tube6"
every = 100
formats = ["xdmf", "vtk"]
render = true
render_every = 0
checkpoint_every = 1000
)";

// A minimal periodic case followed by `extra` lines.
std::string minimal(const std::string& extra = "") {
  return "[domain]\nbox = [10, 10, 10]\nmean_velocity = [0, 0, 1]\n" + extra;
}

// The message of the CaseError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, const fs::path& file = "bad.toml") {
  try {
    parse_case(text, file);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(Case, ContractExampleReadsEveryKey) {
  const Case c = parse_case(kFull, "cases/tube6.toml");
  EXPECT_EQ(c.title, "27 cells");
  EXPECT_EQ(c.domain.kind, DomainKind::periodic);
  EXPECT_EQ(c.domain.box, (Vec3{6.6, 6.6, 12.0}));
  ASSERT_TRUE(c.domain.mean_velocity);
  EXPECT_EQ(*c.domain.mean_velocity, (Vec3{0, 0, 5}));
  EXPECT_FALSE(c.domain.pressure_gradient);
  ASSERT_TRUE(c.vessel);
  EXPECT_EQ(c.vessel->kind, VesselKind::tube);
  EXPECT_EQ(c.vessel->diameter, 6.0);
  EXPECT_EQ(c.vessel->axis, 2);
  ASSERT_TRUE(c.cells);
  EXPECT_EQ(c.cells->count, 27);
  EXPECT_FALSE(c.cells->hematocrit);
  EXPECT_EQ(c.cells->order, 16);
  EXPECT_EQ(c.cells->dealias, 3);
  EXPECT_EQ(c.cells->body_force, (Vec3{0, 0, -1}));
  ASSERT_TRUE(c.cells->perturbation);
  EXPECT_EQ(c.cells->perturbation->l, 4);
  EXPECT_EQ(c.cells->perturbation->m, 2);
  EXPECT_EQ(c.cells->membrane.dilatation_modulus, 200.0);  // an integer where a float is expected
  EXPECT_EQ(c.ewald.grid, (std::array<int, 3>{64, 64, 128}));
  EXPECT_EQ(c.ewald.spline_order, 6);
  EXPECT_EQ(c.solver.patch_radial_points, 24);
  EXPECT_EQ(c.solver.wall_preconditioner_block_nodes, 2000);
  EXPECT_FALSE(c.time.dt);  // "auto"
  EXPECT_EQ(c.output.dir, fs::path("out/tube6"));
  EXPECT_TRUE(c.output.xdmf && c.output.vtk);
  // Lines are recorded for later messages.
  EXPECT_EQ(c.source.line("cells.order"), 18);
  EXPECT_EQ(c.source.line("cells.nonexistent"), 15);  // falls back to the table's line
}

TEST(Case, DefaultsAreFilledIn) {
  const Case c = parse_case(minimal(), "dir/my_case.toml");
  EXPECT_EQ(c.title, "my_case");
  EXPECT_EQ(c.output.dir, fs::path("out/my_case"));
  EXPECT_EQ(c.domain.viscosity_ratio, 5.0);
  EXPECT_FALSE(c.vessel);
  EXPECT_FALSE(c.cells);
  EXPECT_EQ(c.ewald.tolerance, 1e-6);
  EXPECT_FALSE(c.ewald.alpha);
  EXPECT_EQ(c.solver.max_iterations, 100);
  EXPECT_FALSE(c.solver.patch_radial_points);  // libsolver's default for the order
  EXPECT_EQ(c.solver.wall_preconditioner_block_nodes, 500);
  EXPECT_EQ(c.time.end, 10.0);
  EXPECT_EQ(c.time.scheme, TimeSchemeKind::euler);
  EXPECT_EQ(c.output.every, 100);
  EXPECT_EQ(c.output.checkpoint_every, 1000);
  const Case cells = parse_case(minimal("[cells]\n"), "x.toml");
  ASSERT_TRUE(cells.cells);
  EXPECT_EQ(cells.cells->count, 1);
  EXPECT_EQ(cells.cells->shape, CellShape::rbc);
  EXPECT_EQ(cells.cells->narrow_start, NarrowStartKind::stretched);
  EXPECT_EQ(cells.cells->membrane.shear_modulus, 12.4);
  EXPECT_EQ(cells.cells->membrane.bending_modulus, 0.0669);
}

TEST(Case, AlternativesAreRead) {
  const Case free = parse_case(
      "[domain]\nkind = \"free\"\nviscosity_ratio = 1\n"
      "background_flow = { kind = \"shear\", rate = 2.0 }\n[cells]\nshape = \"ellipsoid\"\n"
      "semi_axes = [0.5, 1, 1.5]\npositions = [[0, 0, 0]]\norientations = [[1, 0, 0]]\n",
      "f.toml");
  EXPECT_EQ(free.domain.kind, DomainKind::free);
  EXPECT_EQ(free.domain.background_flow, (BackgroundFlow{FlowKind::shear, 2.0}));
  EXPECT_EQ(free.cells->semi_axes, (Vec3{0.5, 1, 1.5}));
  EXPECT_EQ(free.cells->count, 1);  // from the positions
  const Case ext = parse_case(
      "[domain]\nkind = \"free\"\nbackground_flow = { kind = \"extensional\", rate = 0.5 }\n", "e.toml");
  EXPECT_EQ(ext.domain.background_flow.kind, FlowKind::extensional);

  const Case grad = parse_case(
      "[domain]\nbox = [6, 6, 10]\npressure_gradient = [0, 0, -2]\n[vessel]\nkind = \"constriction\"\n"
      "diameter = 3.5\ndepth = 2.2\nwidth = 1.2\n[cells]\nhematocrit = 0.2\n"
      "[time]\ndt = 1e-3\nscheme = \"ab2\"\n[output]\nformats = [\"vtk\"]\n",
      "g.toml");
  EXPECT_EQ(*grad.domain.pressure_gradient, (Vec3{0, 0, -2}));
  EXPECT_EQ(grad.vessel->center, 5.0);  // default: the middle of the box along the axis
  EXPECT_EQ(grad.cells->hematocrit, 0.2);
  EXPECT_FALSE(grad.cells->count);
  EXPECT_EQ(grad.time.dt, 1e-3);
  EXPECT_EQ(grad.time.scheme, TimeSchemeKind::ab2);
  EXPECT_FALSE(grad.output.xdmf);
  EXPECT_TRUE(grad.output.vtk);

  const Case bif = parse_case(minimal("[vessel]\nkind = \"bifurcation\"\ndiameter = 4\n"), "b.toml");
  EXPECT_NEAR(bif.vessel->daughter_diameters[0], 4 / std::cbrt(2.0), 1e-15);  // Murray's law
  EXPECT_EQ(bif.vessel->angle_deg, 60.0);
  EXPECT_EQ(bif.vessel->fillet_radius, 0.0);  // sharp junctions unless asked
}

TEST(Case, VesselFileIsRelativeToTheCaseFile) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_case_file";
  fs::create_directories(dir / "vessels");
  std::ofstream(dir / "vessels" / "my.stl") << "solid x\nendsolid x\n";
  const Case c = parse_case(minimal("[vessel]\nkind = \"file\"\npath = \"vessels/my.stl\"\n"), dir / "c.toml");
  EXPECT_EQ(c.vessel->path, dir / "vessels" / "my.stl");
  const std::string e = error_of(minimal("[vessel]\nkind = \"file\"\npath = \"vessels/none.msh\"\n"), dir / "c.toml");
  EXPECT_TRUE(contains(e, ":6: vessel.path: no such file")) << e;
  fs::remove_all(dir);
}

TEST(Case, WrittenCaseReadsBackEqual) {
  const fs::path dir = fs::temp_directory_path() / "rbcflow_test_case_roundtrip";
  fs::create_directories(dir);
  std::ofstream(dir / "wall.msh") << "$MeshFormat\n";
  const std::vector<std::string> cases = {
      kFull,
      minimal(),
      "title = \"quote \\\" and \\\\ backslash\"\n[domain]\nkind = \"free\"\n"
      "background_flow = { kind = \"shear\", rate = 0.1 }\n[cells]\nshape = \"ellipsoid\"\n"
      "positions = [[0.1, 0.2, 0.3], [3, 0, 0]]\norientations = [[1, 1, 0], [0, 0, 1]]\n"
      "[cells.membrane]\nlaw = \"neo-hookean\"\n[time]\ndt = 0.001\n",
      minimal("[vessel]\nkind = \"bifurcation\"\ndiameter = 4\ndaughter_diameters = [3, 2.5]\nfillet_radius = 0.5\n"
              "[cells]\nhematocrit = 0.3\nnarrow_start = \"parachute\"\n[output]\nformats = []\nrender_view = \"end\"\n"),
      minimal("[vessel]\nkind = \"file\"\npath = \"wall.msh\"\nscale = 0.354\n[ewald]\ngrid = [8, 8, 8]\n"),
      "[domain]\nbox = [5, 5, 10]\ntube_velocity = 2.5\n[vessel]\nkind = \"constriction\"\ndiameter = 3.5\n"
      "depth = 2.2\nwidth = 1.2\ncenter = 5\n",
  };
  for (const std::string& text : cases) {
    const Case c = parse_case(text, dir / "in.toml");
    write_case_toml(c, dir / "case.toml");
    const Case back = read_case(dir / "case.toml");
    EXPECT_EQ(back, c) << case_toml(c);
    EXPECT_EQ(case_toml(back), case_toml(c));
    EXPECT_EQ(case_fingerprint(back), case_fingerprint(c));
  }
  fs::remove_all(dir);
}

TEST(Case, FingerprintIgnoresOutputTitleEndTimeAndPreconditionerOnly) {
  const Case a = parse_case(kFull, "a.toml");
  Case b = a;
  b.title = "other";
  b.output.dir = "elsewhere";
  b.time.end = 20;
  b.solver.wall_preconditioner_block_nodes = 100000;
  EXPECT_EQ(case_fingerprint(a), case_fingerprint(b));
  EXPECT_EQ(case_fingerprint(a).size(), 16u);
  b.cells->order = 12;
  EXPECT_NE(case_fingerprint(a), case_fingerprint(b));
  Case c = a;
  c.domain.mean_velocity = Vec3{0, 0, 5.000000001};
  EXPECT_NE(case_fingerprint(a), case_fingerprint(c));
  // The contact repulsion is physics; off, it is not written, so cases from before its keys
  // existed keep their fingerprints.
  Case d = a;
  d.time.contact_range = 0.1;
  d.time.contact_strength = 100.0;
  EXPECT_NE(case_fingerprint(a), case_fingerprint(d));
  EXPECT_EQ(case_toml(a).find("contact_"), std::string::npos);
  EXPECT_EQ(parse_case(case_toml(d), "d.toml").time, d.time);
}

TEST(Case, MalformedTomlNamesFileAndLine) {
  const std::string e = error_of("[domain]\nbox = [1, 2\n", "broken.toml");
  EXPECT_TRUE(contains(e, "broken.toml:")) << e;
  EXPECT_TRUE(contains(e, "malformed TOML")) << e;
  const std::string twice = error_of("[domain]\nbox = [1, 1, 1]\nbox = [2, 2, 2]\n");
  EXPECT_TRUE(contains(twice, "bad.toml:3: malformed TOML")) << twice;
  EXPECT_TRUE(contains(error_of("\xff\xfe garbage = = ="), "malformed TOML"));
}

TEST(Case, TextThatIsNotUtf8IsRejectedBeforeToml11SeesIt) {
  // toml11 3.7.1 reads past its buffer reporting invalid UTF-8 in a literal string (found by
  // the fuzzer; tests/io/fuzz/regressions). Every malformed sequence is caught first.
  EXPECT_EQ(error_of("[domain]\nbox = [6, 6,' \xff\x31'\n"), "bad.toml:2: malformed TOML: not UTF-8 (byte 23 of the file)");
  for (const char* bad : {"\xc0\xaf", "\xe0\x80\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xe2\x82", "\x80"}) {
    EXPECT_TRUE(contains(error_of(std::string("title = \"") + bad + "\"\n"), "not UTF-8")) << bad;
  }
  // Well-formed UTF-8 of every length passes.
  const Case c = parse_case(minimal() + "# \xc3\xa9 \xe2\x82\xac \xf0\x9f\xa9\xb8\n", "ok.toml");
  EXPECT_EQ(c.domain.box[0], 10.0);
}

TEST(Case, UnknownKeysAreErrors) {
  EXPECT_EQ(error_of(minimal("[cells]\norder = 8\nordr = 9\n")), "bad.toml:6: cells.ordr: unknown key in [cells]");
  EXPECT_EQ(error_of("colour = 1\n" + minimal()), "bad.toml:1: colour: unknown key");
  EXPECT_EQ(error_of(minimal("[frobnicate]\nx = 1\n")), "bad.toml:4: frobnicate: unknown key");
  EXPECT_TRUE(contains(error_of(minimal("[cells.membrane]\nshear = 1\n")), "cells.membrane.shear: unknown key"));
  EXPECT_TRUE(contains(error_of(minimal("[cells]\nperturbation = { l = 2, n = 1 }\n")),
                       "cells.perturbation.n: unknown key"));
  // Keys of another kind say where they apply.
  EXPECT_EQ(error_of(minimal("[vessel]\ndiameter = 3\ndepth = 1\n")),
            "bad.toml:6: vessel.depth: applies only to kind = \"constriction\"");
  EXPECT_TRUE(contains(error_of(minimal("[cells]\nsemi_axes = [1, 1, 1]\n")), "applies only to shape = \"ellipsoid\""));
}

TEST(Case, WrongTypesAreErrors) {
  EXPECT_EQ(error_of(minimal("[cells]\norder = 16.5\n")),
            "bad.toml:5: cells.order: expected an integer, got a floating-point number");
  EXPECT_EQ(error_of(minimal("[cells]\norder = \"16\"\n")),
            "bad.toml:5: cells.order: expected an integer, got a string");
  EXPECT_EQ(error_of("[domain]\nbox = 10\nmean_velocity = [0, 0, 1]\n"),
            "bad.toml:2: domain.box: expected an array of 3 numbers, got an integer");
  EXPECT_EQ(error_of("[domain]\nbox = [10, 10]\nmean_velocity = [0, 0, 1]\n"),
            "bad.toml:2: domain.box: expected an array of 3 numbers, got 2 elements");
  EXPECT_EQ(error_of(minimal("[time]\nvolume_constraint = 1\n")),
            "bad.toml:5: time.volume_constraint: expected true or false, got an integer");
  EXPECT_EQ(error_of(minimal("[time]\ndt = \"fast\"\n")),
            "bad.toml:5: time.dt: \"fast\" is not allowed (a number or \"auto\")");
  EXPECT_EQ(error_of("cells = 3\n" + minimal()), "bad.toml:1: cells: expected a table, got an integer");
  EXPECT_EQ(error_of(minimal("[cells]\nshape = \"cube\"\n")),
            "bad.toml:5: cells.shape: \"cube\" is not allowed (allowed: \"rbc\", \"sphere\", \"ellipsoid\")");
  EXPECT_EQ(error_of(minimal("[cells]\nnarrow_start = \"sideways\"\n")),
            "bad.toml:5: cells.narrow_start: \"sideways\" is not allowed (allowed: \"stretched\", \"parachute\")");
  EXPECT_TRUE(contains(error_of(minimal("[output]\nformats = [\"xdmf\", \"png\"]\n")), "output.formats"));
  EXPECT_TRUE(contains(error_of(minimal("[output]\nformats = [\"vtk\", \"vtk\"]\n")), "listed twice"));
}

TEST(Case, OutOfRangeValuesNameTheAllowedRange) {
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"bifurcation\"\ndiameter = 4\ndaughter_diameters = [3, 2.4]\n"
                             "fillet_radius = 1.2\n")),
            "bad.toml:8: vessel.fillet_radius: 1.2 is out of range (allowed: 0 <= x < 1.2)");
  EXPECT_EQ(error_of(minimal("[cells]\norder = 3\n")),
            "bad.toml:5: cells.order: 3 is out of range (allowed: integers 4..128)");
  EXPECT_EQ(error_of(minimal("[cells]\norder = 129\n")),
            "bad.toml:5: cells.order: 129 is out of range (allowed: integers 4..128)");
  EXPECT_EQ(error_of(minimal("[cells]\ndealias = 0\n")),
            "bad.toml:5: cells.dealias: 0 is out of range (allowed: integers 1..4)");
  EXPECT_EQ(error_of("[domain]\nbox = [10, -1, 10]\nmean_velocity = [0, 0, 1]\n"),
            "bad.toml:2: domain.box: -1 is out of range (allowed: 0 < x)");
  EXPECT_EQ(error_of("[domain]\nbox = [10, 0, 10]\nmean_velocity = [0, 0, 1]\n"),
            "bad.toml:2: domain.box: 0 is out of range (allowed: 0 < x)");
  EXPECT_EQ(error_of("[domain]\nbox = [10, nan, 10]\nmean_velocity = [0, 0, 1]\n"),
            "bad.toml:2: domain.box: nan is out of range (allowed: 0 < x)");
  EXPECT_EQ(error_of(minimal("[vessel]\ndiameter = 12\n")),
            "bad.toml:5: vessel.diameter: 12 is out of range (allowed: 0 < x < 10)");
  EXPECT_EQ(error_of(minimal("[vessel]\ndiameter = 4\nelement_size = 0\n")),
            "bad.toml:6: vessel.element_size: 0 is out of range (allowed: 0 < x <= 2)");
  // A default that the other values put out of range (0.25 in a vessel of radius 0.1: a
  // diameter in metres, say) is named as a value would be (found by fuzz.case_toml_short: the
  // case read, and its written form did not).
  EXPECT_EQ(error_of(minimal("[vessel]\ndiameter = 0.2\n")),
            "bad.toml:4: vessel.element_size: the default 0.25 is out of range here (allowed: 0 < x <= 0.1); set it");
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"constriction\"\ndiameter = 3.5\ndepth = 3.5\nwidth = 1\n")),
            "bad.toml:7: vessel.depth: 3.5 is out of range (allowed: 0 < x < 3.5)");
  EXPECT_EQ(error_of(minimal("[time]\nend = -1\n")), "bad.toml:5: time.end: -1 is out of range (allowed: 0 < x)");
  EXPECT_EQ(error_of(minimal("[time]\nend = 1\ndt = 2\n")),
            "bad.toml:6: time.dt: 2 is out of range (allowed: 0 < x <= 1)");
  EXPECT_EQ(error_of(minimal("[cells.membrane]\nshear_modulus = 0\n")),
            "bad.toml:5: cells.membrane.shear_modulus: 0 is out of range (allowed: 0 < x)");
  EXPECT_EQ(error_of(minimal("[ewald]\ncutoff = 161\n")),
            "bad.toml:5: ewald.cutoff: 161 is out of range (allowed: 0 < x <= 160)");
  EXPECT_EQ(error_of(minimal("[ewald]\ntolerance = 1e-12\n")),
            "bad.toml:5: ewald.tolerance: 1e-12 is out of range (allowed: 1e-10 <= x <= 0.001)");
  EXPECT_EQ(error_of(minimal("[ewald]\nspline_order = 6\ngrid = [16, 10, 16]\n")),
            "bad.toml:6: ewald.grid: 10 is out of range (allowed: integers 12..4096)");
  EXPECT_EQ(error_of(minimal("[ewald]\ngrid = [16, 17, 16]\n")), "bad.toml:5: ewald.grid: 17 is odd (grid sides are even)");
  EXPECT_EQ(error_of(minimal("[solver]\npatch_radial_points = 2\n")),
            "bad.toml:5: solver.patch_radial_points: 2 is out of range (allowed: integers 4..64)");
  EXPECT_EQ(error_of(minimal("[solver]\nwall_preconditioner_block_nodes = 0\n")),
            "bad.toml:5: solver.wall_preconditioner_block_nodes: 0 is out of range (allowed: integers 1..10000000)");
  EXPECT_EQ(error_of(minimal("[output]\nevery = 0\n")),
            "bad.toml:5: output.every: 0 is out of range (allowed: integers 1..2147483647)");
  EXPECT_EQ(error_of(minimal("[cells]\norder = 99999999999999\n")),
            "bad.toml:5: cells.order: 99999999999999 is out of range (allowed: integers 4..128)");
  EXPECT_TRUE(contains(error_of(minimal("[cells]\norder = 8\nperturbation = { l = 8 }\n")),
                       "cells.perturbation.l: 8 is out of range (allowed: integers 0..7)"));
}

TEST(Case, InconsistentKeysAreErrors) {
  EXPECT_EQ(error_of("[domain]\nbox = [1, 1, 1]\n"),
            "bad.toml:1: [domain]: a periodic domain needs mean_velocity, pressure_gradient, tube_velocity or "
            "pseudo_shear_rate (mean_velocity = [0, 0, 0] for no imposed flow)");
  EXPECT_EQ(error_of(minimal("pressure_gradient = [0, 0, 1]\n")),
            "bad.toml:4: domain.pressure_gradient: give mean_velocity or pressure_gradient, not both");
  EXPECT_EQ(error_of("[domain]\nmean_velocity = [0, 0, 1]\n"),
            "bad.toml:1: [domain]: box = [L1, L2, L3] is required for kind = \"periodic\"");
  EXPECT_TRUE(contains(error_of("title = \"x\"\n"), "missing table [domain]"));
  EXPECT_TRUE(contains(error_of("[domain]\nkind = \"free\"\nbox = [1, 1, 1]\n"),
                       "bad.toml:3: domain.box: applies only to kind = \"periodic\""));
  EXPECT_TRUE(contains(error_of("[domain]\nkind = \"free\"\n[vessel]\ndiameter = 1\n"),
                       "vessel: a vessel needs [domain] kind = \"periodic\""));
  EXPECT_EQ(error_of(minimal("[cells]\ncount = 2\nhematocrit = 0.2\n")),
            "bad.toml:6: cells.hematocrit: give count or hematocrit, not both");
  EXPECT_TRUE(contains(error_of(minimal("[cells]\nhematocrit = 0.2\n")), "needs a [vessel]"));
  EXPECT_EQ(error_of("[domain]\nkind = \"free\"\n[cells]\ncount = 2\n"),
            "bad.toml:3: [cells]: cells in a free domain need positions (e.g. positions = [[0, 0, 0]])");
  EXPECT_EQ(error_of(minimal("[cells]\ncount = 3\npositions = [[1, 1, 1], [2, 2, 2]]\n")),
            "bad.toml:5: cells.count: 3 cells but 2 positions");
  EXPECT_TRUE(contains(error_of(minimal("[cells]\npositions = [[1, 1, 1]]\norientations = [[0, 0, 0]]\n")),
                       "orientations[0] is the zero vector"));
  EXPECT_TRUE(contains(error_of(minimal("[vessel]\nkind = \"constriction\"\ndiameter = 3\n")),
                       "depth and width are required"));
  EXPECT_TRUE(contains(error_of(minimal("[vessel]\ndiameter = 3\nfillet_radius = 0.5\n")),
                       "vessel.fillet_radius: applies only to kind = \"bifurcation\" or \"network\""));
  EXPECT_TRUE(contains(error_of(minimal("[time]\ndt = 0.1\ndt_safety = 0.5\n")), "applies only to dt = \"auto\""));
  // The contact repulsion: a range needs a strength, a strength a range, and the range must
  // exceed h_s (the repulsion acts between the two).
  EXPECT_TRUE(contains(error_of(minimal("[time]\ncontact_range = 0.1\n")),
                       "time.contact_strength: is needed with contact_range"));
  EXPECT_TRUE(contains(error_of(minimal("[time]\ncontact_strength = 100\n")),
                       "time.contact_strength: applies only to a contact_range above 0"));
  EXPECT_TRUE(contains(error_of(minimal("[time]\ncontact_range = 0.02\ncontact_strength = 100\n")),
                       "time.contact_range: must exceed collision_threshold"));
  EXPECT_TRUE(contains(error_of(minimal("[time]\ncontact_range = 0.1\ncontact_strength = 0\n")), "out of range"));
  EXPECT_TRUE(contains(error_of(minimal("[cells.membrane]\nlaw = \"neo-hookean\"\ndilatation_modulus = 1\n")),
                       "applies only to law"));
}

TEST(Case, CellsOutsideTheBoxAreErrors) {
  EXPECT_EQ(error_of(minimal("[cells]\npositions = [\n  [1, 1, 1],\n  [5, 10, 5],\n]\n")),
            "bad.toml:5: cells.positions: positions[1] = [5, 10, 5] lies outside the box "
            "[0, 10) x [0, 10) x [0, 10)");
  EXPECT_TRUE(contains(error_of(minimal("[cells]\npositions = [[-0.1, 1, 1]]\n")), "lies outside the box"));
  EXPECT_EQ(error_of(minimal("[cells]\npositions = [\n  [1, 1, 1],\n  [5, 5],\n]\n")),
            "bad.toml:7: cells.positions[1]: expected an array of 3 numbers, got 2 elements");
}

TEST(Case, UnreadableFileIsAnError) {
  try {
    read_case("/nonexistent/case.toml");
    FAIL();
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/case.toml: cannot read the case file");
  }
}

// [units] (section 6's scales by default) and the drive given as a pseudo-shear rate in 1/s.
TEST(Case, UnitsAndPseudoShearRate) {
  const std::string tube = "[domain]\nbox = [5, 5, 4]\npseudo_shear_rate = 200\n[vessel]\ndiameter = 3.5\n";
  const Case c = parse_case(tube, "t.toml");
  ASSERT_TRUE(c.domain.pseudo_shear_rate);
  EXPECT_EQ(*c.domain.pseudo_shear_rate, 200.0);
  EXPECT_EQ(c.units.length_um, 2.82);
  EXPECT_EQ(c.units.rate_per_s, 100.0);
  EXPECT_EQ(c.units.plasma_viscosity_mpas, 1.2);
  const Case u = parse_case(tube + "[units]\nlength_um = 3.0\nrate_per_s = 50\nplasma_viscosity_mpas = 1.0\n", "t.toml");
  EXPECT_EQ(u.units.length_um, 3.0);
  EXPECT_EQ(u.units.rate_per_s, 50.0);
  EXPECT_EQ(u.units.plasma_viscosity_mpas, 1.0);
  EXPECT_EQ(parse_case(case_toml(u), "t.toml"), u);
  EXPECT_NE(case_fingerprint(u), case_fingerprint(c));
  // With the default scales a case hashes as it did before [units] (this one at 8968d70:
  // rbcflow run's message for a checkpoint of another case), so its checkpoints still fit.
  const Case walls = parse_case("[domain]\nbox = [5.0, 5.0, 3.0]\ntube_velocity = 1.0\nviscosity_ratio = 1.0\n"
                                "[vessel]\ndiameter = 3.5\nelement_size = 0.5\n[time]\nend = 0.02\ndt = 0.01\n",
                                "fp.toml");
  EXPECT_EQ(case_fingerprint(walls), "54010ac9f69d08f2");

  EXPECT_EQ(error_of(tube + "[units]\nrate_per_s = 0\n"),
            "bad.toml:7: units.rate_per_s: 0 is out of range (allowed: 0 < x <= 1e+09)");
  EXPECT_TRUE(contains(error_of(tube + "[units]\nlength = 3\n"), "bad.toml:7: units.length: unknown key"));
  EXPECT_EQ(error_of("[domain]\nbox = [5, 5, 4]\ntube_velocity = 2\npseudo_shear_rate = 100\n[vessel]\ndiameter = 3.5\n"),
            "bad.toml:4: domain.pseudo_shear_rate: give tube_velocity or pseudo_shear_rate, not both");
  EXPECT_EQ(error_of("[domain]\nbox = [5, 5, 4]\npseudo_shear_rate = 100\n"),
            "bad.toml:3: domain.pseudo_shear_rate: needs a [vessel] of kind \"tube\", \"constriction\" or "
            "\"bifurcation\" (the flow in its straight (parent) section sets <u>); use mean_velocity or "
            "pressure_gradient otherwise");
  EXPECT_TRUE(contains(error_of("[domain]\nbox = [5, 5, 4]\npseudo_shear_rate = -5\n[vessel]\ndiameter = 3.5\n"),
                       "domain.pseudo_shear_rate: -5 is out of range"));
}

TEST(Case, TubeVelocityDrivesATubeConstrictionOrBifurcationOnly) {
  const Case c = parse_case("[domain]\nbox = [5, 5, 4]\ntube_velocity = 2\n[vessel]\ndiameter = 3.5\n", "t.toml");
  ASSERT_TRUE(c.domain.tube_velocity);
  EXPECT_EQ(*c.domain.tube_velocity, 2.0);
  EXPECT_FALSE(c.domain.mean_velocity);
  EXPECT_FALSE(c.domain.pressure_gradient);
  EXPECT_EQ(error_of("[domain]\nbox = [5, 5, 4]\ntube_velocity = 2\n"),
            "bad.toml:3: domain.tube_velocity: needs a [vessel] of kind \"tube\", \"constriction\" or \"bifurcation\" "
            "(the flow in its straight (parent) section sets <u>); use mean_velocity or pressure_gradient otherwise");
  EXPECT_TRUE(parse_case("[domain]\nbox = [8, 8, 8]\ntube_velocity = 2\n[vessel]\nkind = \"bifurcation\"\n"
                         "diameter = 3\ndaughter_diameters = [2, 2]\n", "b.toml").domain.tube_velocity);
  EXPECT_TRUE(contains(error_of("[domain]\nbox = [8, 8, 8]\ntube_velocity = 2\n[vessel]\nkind = \"network\"\n"
                                "segments = [{ from = [4, 4, 0], to = [4, 4, 8], diameter = 3 }]\n"),
                       "bad.toml:3: domain.tube_velocity: needs a [vessel] of kind"));
  EXPECT_EQ(error_of(minimal("tube_velocity = 2\n")),
            "bad.toml:4: domain.tube_velocity: give mean_velocity or tube_velocity, not both");
  EXPECT_EQ(error_of("[domain]\nbox = [5, 5, 4]\npressure_gradient = [0, 0, -1]\ntube_velocity = 2\n"),
            "bad.toml:4: domain.tube_velocity: give pressure_gradient or tube_velocity, not both");
  EXPECT_TRUE(contains(error_of("[domain]\nkind = \"free\"\ntube_velocity = 2\n"),
                       "bad.toml:3: domain.tube_velocity: applies only to kind = \"periodic\""));
  EXPECT_TRUE(contains(error_of("[domain]\nbox = [5, 5, 4]\ntube_velocity = nan\n[vessel]\ndiameter = 3.5\n"),
                       "domain.tube_velocity: nan is out of range"));
}

TEST(Case, CaseErrorNamesTheLineOfALaterCheck) {
  const Case c = parse_case(minimal("[cells]\npositions = [[1, 1, 1]]\n"), "later.toml");
  EXPECT_EQ(std::string(case_error(c, "cells.positions", "cells 0 and 1 overlap").what()),
            "later.toml:5: cells.positions: cells 0 and 1 overlap");
}

TEST(Case, EveryExampleCaseReadsAndRoundTrips) {
  int cases = 0;
  const fs::path out = fs::temp_directory_path() / "rbcflow_test_examples";
  fs::create_directories(out);
  for (const auto& entry : fs::directory_iterator(RBCFLOW_CASES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    const Case c = read_case(entry.path());
    write_case_toml(c, out / "case.toml");
    EXPECT_EQ(read_case(out / "case.toml"), c);
    ++cases;
  }
  EXPECT_GE(cases, 7);
  fs::remove_all(out);
}

// A network's segments are read as a list of { from, to, diameter } tables; each error names the
// segment's key and line (the geometry is checked where the network is built).
TEST(Case, NetworkSegmentsAreRead) {
  const std::string network = "[vessel]\nkind = \"network\"\nsegments = [\n"
                              "  { from = [5, 5, 0], to = [5, 5, 5], diameter = 3 },\n"
                              "  { from = [5, 5, 5], to = [5, 5, 10], diameter = 2.5 },\n]\n";
  const Case c = parse_case(minimal(network), "net.toml");
  ASSERT_TRUE(c.vessel);
  EXPECT_EQ(c.vessel->kind, VesselKind::network);
  ASSERT_EQ(c.vessel->segments.size(), 2u);
  EXPECT_EQ(c.vessel->segments[1].from, (Vec3{5, 5, 5}));
  EXPECT_EQ(c.vessel->segments[1].diameter, 2.5);
  EXPECT_EQ(parse_case(minimal(network + "fillet_radius = 0.5\n"), "net.toml").vessel->fillet_radius, 0.5);
  EXPECT_EQ(error_of(minimal(network + "fillet_radius = 1.25\n")),
            "bad.toml:10: vessel.fillet_radius: 1.25 is out of range (allowed: 0 <= x < 1.25)");
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"network\"\n")),
            "bad.toml:4: [vessel]: segments = [{ from = [x, y, z], to = [x, y, z], diameter = d }, ...] is required "
            "for kind = \"network\"");
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"network\"\nsegments = [{ from = [1, 1, 0], to = [1, 1, 2] }]\n")),
            "bad.toml:6: [vessel.segments[0]]: from, to and diameter are required");
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"network\"\nsegments = [\n{ from = [1, 1, 0], to = [1, 1, 2], "
                             "diameter = 1 },\n{ from = [1, 1], to = [1, 1, 2], diameter = 1 }]\n")),
            "bad.toml:8: vessel.segments[1].from: expected an array of 3 numbers, got 2 elements");
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"network\"\nsegments = [{ from = [1, 1, 0], to = [1, 1, 2], "
                             "diameter = 1, radius = 0.5 }]\n")),
            "bad.toml:6: vessel.segments[0].radius: unknown key in [vessel.segments[0]]");
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"network\"\nsegments = [3]\n")),
            "bad.toml:6: vessel.segments[0]: expected a table { from, to, diameter }, got an integer");
  EXPECT_EQ(error_of(minimal("[vessel]\nkind = \"network\"\ndiameter = 3\nsegments = []\n")),
            "bad.toml:6: vessel.diameter: applies only to kind = \"tube\", \"constriction\" or \"bifurcation\"");
  EXPECT_EQ(error_of(minimal("[vessel]\ndiameter = 3\nsegments = []\n")),
            "bad.toml:6: vessel.segments: applies only to kind = \"network\"");
}
