// Reading and validating case files. The only file that includes toml11 (about 10 s of
// compile time per file). Keys, defaults and ranges: docs/case-format.md.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <toml.hpp>
#include <utility>

#include "io/case.h"

namespace rbcflow {
namespace {

namespace fs = std::filesystem;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string type_name(const toml::value& v) {
  switch (v.type()) {
    case toml::value_t::boolean: return "a boolean";
    case toml::value_t::integer: return "an integer";
    case toml::value_t::floating: return "a floating-point number";
    case toml::value_t::string: return "a string";
    case toml::value_t::array: return "an array";
    case toml::value_t::table: return "a table";
    default: return "a date or time";
  }
}

std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// An interval of allowed values, printed in messages as "0 < x <= 1".
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;

  bool contains(double x) const {
    return std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string text() const {
    std::string t;
    if (lo > -kInf) t.append(number_text(lo)).append(lo_open ? " < " : " <= ");
    t.append("x");
    if (hi < kInf) t.append(hi_open ? " < " : " <= ").append(number_text(hi));
    if (lo == -kInf && hi == kInf) t = "any finite number";
    return t;
  }
};
Range positive() { return {0, kInf, true, false}; }
Range non_negative() { return {0, kInf, false, false}; }
Range any_finite() { return {}; }
Range closed(double lo, double hi) { return {lo, hi, false, false}; }
Range open_closed(double lo, double hi) { return {lo, hi, true, false}; }
Range open(double lo, double hi) { return {lo, hi, true, true}; }
Range closed_open(double lo, double hi) { return {lo, hi, false, true}; }

// Collects the lines of the keys read, for messages now and later (CaseSource).
class Context {
 public:
  Context(fs::path file, CaseSource& source) : file_(std::move(file)), source_(source) {}

  [[noreturn]] void fail(int line, const std::string& key, const std::string& why) const {
    std::string m = file_.string();
    if (line > 0) m.append(":").append(std::to_string(line));
    m.append(": ");
    if (!key.empty()) m.append(key).append(": ");
    m.append(why);
    throw CaseError(m);
  }
  void record(const std::string& key, int line) { source_.lines[key] = line; }
  const fs::path& file() const { return file_; }

 private:
  fs::path file_;
  CaseSource& source_;
};

int line_of(const toml::value& v) { return static_cast<int>(v.location().line()); }

// One TOML table: typed getters with defaults and ranges; finish() rejects unread keys.
class Table {
 public:
  Table(const toml::value& v, std::string name, Context& ctx)
      : v_(&v), name_(std::move(name)), ctx_(&ctx) {}

  std::string key_name(const std::string& key) const {
    return name_.empty() ? key : name_ + "." + key;
  }
  int line() const { return name_.empty() ? 0 : line_of(*v_); }
  bool has(const std::string& key) const { return v_->as_table().count(key) > 0; }

  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    const auto& t = v_->as_table();
    const auto it = t.find(key);
    ctx_->fail(it == t.end() ? line() : line_of(it->second), key_name(key), why);
  }
  // An error about a value (an array element has its own line).
  [[noreturn]] void fail_value(const toml::value& v, const std::string& key, const std::string& why) const {
    ctx_->fail(line_of(v), key_name(key), why);
  }
  // An error about the table as a whole (a missing key, inconsistent keys).
  [[noreturn]] void fail_table(const std::string& why) const {
    ctx_->fail(line(), name_.empty() ? "" : "[" + name_ + "]", why);
  }

  // The value of `key`, or nullptr; marks the key as read and records its line.
  const toml::value* get(const std::string& key) {
    const auto& t = v_->as_table();
    const auto it = t.find(key);
    if (it == t.end()) return nullptr;
    read_.insert(key);
    ctx_->record(key_name(key), line_of(it->second));
    return &it->second;
  }

  double to_real(const std::string& key, const toml::value& v, const Range& r) const {
    double x = 0;
    if (v.is_integer()) {
      x = static_cast<double>(v.as_integer());
    } else if (v.is_floating()) {
      x = v.as_floating();
    } else {
      fail_value(v, key, "expected a number, got " + type_name(v));
    }
    if (!r.contains(x)) fail_value(v, key, number_text(x) + " is out of range (allowed: " + r.text() + ")");
    return x;
  }
  std::optional<double> optional_real(const std::string& key, const Range& r) {
    const toml::value* v = get(key);
    if (!v) return std::nullopt;
    return to_real(key, *v, r);
  }
  // The value of `key`, or `fallback` where it is absent; a default out of the range that the
  // case's other values set (an element size larger than a thin vessel's radius) is an error,
  // as the same value written out would be.
  double real(const std::string& key, double fallback, const Range& r) {
    if (const std::optional<double> x = optional_real(key, r)) return *x;
    if (!r.contains(fallback))
      fail(key, "the default " + number_text(fallback) + " is out of range here (allowed: " + r.text() + "); set it");
    return fallback;
  }

  int to_integer(const std::string& key, const toml::value& v, long lo, long hi) const {
    if (!v.is_integer()) fail_value(v, key, "expected an integer, got " + type_name(v));
    const auto x = v.as_integer();
    if (x < lo || x > hi) {
      fail_value(v, key, std::to_string(x) + " is out of range (allowed: integers " + std::to_string(lo) +
                    ".." + std::to_string(hi) + ")");
    }
    return static_cast<int>(x);
  }
  std::optional<int> optional_integer(const std::string& key, long lo, long hi) {
    const toml::value* v = get(key);
    if (!v) return std::nullopt;
    return to_integer(key, *v, lo, hi);
  }
  int integer(const std::string& key, int fallback, long lo, long hi) {
    return optional_integer(key, lo, hi).value_or(fallback);
  }

  bool boolean(const std::string& key, bool fallback) {
    const toml::value* v = get(key);
    if (!v) return fallback;
    if (!v->is_boolean()) fail(key, "expected true or false, got " + type_name(*v));
    return v->as_boolean();
  }

  std::optional<std::string> optional_text(const std::string& key) {
    const toml::value* v = get(key);
    if (!v) return std::nullopt;
    if (!v->is_string()) fail(key, "expected a string, got " + type_name(*v));
    return v->as_string().str;
  }

  // One of a fixed set of names.
  template <typename E>
  E choice(const std::string& key, E fallback, const std::vector<std::pair<std::string, E>>& names) {
    const auto text = optional_text(key);
    if (!text) return fallback;
    std::string allowed;
    for (const auto& [name, value] : names) {
      if (name == *text) return value;
      allowed.append(allowed.empty() ? "\"" : ", \"").append(name).append("\"");
    }
    fail(key, "\"" + *text + "\" is not allowed (allowed: " + allowed + ")");
  }

  const toml::array& to_array(const std::string& key, const toml::value& v, std::size_t size,
                              const std::string& what) const {
    if (!v.is_array()) fail_value(v, key, "expected " + what + ", got " + type_name(v));
    const auto& a = v.as_array();
    if (size > 0 && a.size() != size) {
      fail_value(v, key, "expected " + what + ", got " + std::to_string(a.size()) + " elements");
    }
    return a;
  }
  Vec3 to_vec3(const std::string& key, const toml::value& v, const Range& r) const {
    const auto& a = to_array(key, v, 3, "an array of 3 numbers");
    Vec3 x{};
    for (int i = 0; i < 3; ++i) x[i] = to_real(key, a[i], r);
    return x;
  }
  std::optional<Vec3> vec3(const std::string& key, const Range& r) {
    const toml::value* v = get(key);
    if (!v) return std::nullopt;
    return to_vec3(key, *v, r);
  }
  std::vector<Vec3> vec3_list(const std::string& key, const Range& r) {
    const toml::value* v = get(key);
    if (!v) return {};
    const auto& a = to_array(key, *v, 0, "an array of [x, y, z] arrays");
    if (a.empty()) fail(key, "the list is empty");
    std::vector<Vec3> list;
    for (std::size_t i = 0; i < a.size(); ++i) {
      list.push_back(to_vec3(key + "[" + std::to_string(i) + "]", a[i], r));
    }
    return list;
  }
  template <std::size_t K>
  std::optional<std::array<int, K>> int_array(const std::string& key, long lo, long hi) {
    const toml::value* v = get(key);
    if (!v) return std::nullopt;
    const auto& a = to_array(key, *v, K, "an array of " + std::to_string(K) + " integers");
    std::array<int, K> x{};
    for (std::size_t i = 0; i < K; ++i) x[i] = to_integer(key, a[i], lo, hi);
    return x;
  }

  // A table inside one of this table's values (an element of an array of tables).
  Table nested(const toml::value& v, const std::string& key) const { return Table(v, key_name(key), *ctx_); }

  std::optional<Table> table(const std::string& key) {
    const toml::value* v = get(key);
    if (!v) return std::nullopt;
    if (!v->is_table()) fail(key, "expected a table, got " + type_name(*v));
    return Table(*v, key_name(key), *ctx_);
  }

  // Keys of `other_kind` present in a table of another kind.
  void reject(const std::vector<std::string>& keys, const std::string& applies_to) const {
    for (const auto& k : keys) {
      if (has(k)) fail(k, "applies only to " + applies_to);
    }
  }

  // The first key (by line) that was never read is an error.
  void finish() const {
    const std::string* first = nullptr;
    int first_line = std::numeric_limits<int>::max();
    for (const auto& [k, v] : v_->as_table()) {
      if (read_.count(k) == 0 && line_of(v) < first_line) {
        first = &k;
        first_line = line_of(v);
      }
    }
    if (first) fail(*first, "unknown key" + (name_.empty() ? std::string() : " in [" + name_ + "]"));
  }

 private:
  const toml::value* v_;
  std::string name_;
  Context* ctx_;
  std::set<std::string> read_;
};

// ---------------------------------------------------------------------------------------------

CaseDomain read_domain(Table& top) {
  auto t = top.table("domain");
  if (!t) top.fail_table("missing table [domain] (kind = \"periodic\" with a box, or kind = \"free\")");
  CaseDomain d;
  d.kind = t->choice<DomainKind>("kind", DomainKind::periodic,
                                 {{"periodic", DomainKind::periodic}, {"free", DomainKind::free}});
  d.viscosity_ratio = t->real("viscosity_ratio", d.viscosity_ratio, positive());
  if (d.kind == DomainKind::periodic) {
    t->reject({"background_flow"}, "kind = \"free\" (a periodic flow is set by mean_velocity, "
                                   "pressure_gradient or tube_velocity)");
    const auto box = t->vec3("box", positive());
    if (!box) t->fail_table("box = [L1, L2, L3] is required for kind = \"periodic\"");
    d.box = *box;
    d.mean_velocity = t->vec3("mean_velocity", any_finite());
    d.pressure_gradient = t->vec3("pressure_gradient", any_finite());
    d.tube_velocity = t->optional_real("tube_velocity", any_finite());
    d.pseudo_shear_rate = t->optional_real("pseudo_shear_rate", open_closed(0, 1e6));
    // One drive: the first given of these, in this order, names the conflict.
    std::vector<std::string> given;
    if (d.mean_velocity) given.push_back("mean_velocity");
    if (d.pressure_gradient) given.push_back("pressure_gradient");
    if (d.tube_velocity) given.push_back("tube_velocity");
    if (d.pseudo_shear_rate) given.push_back("pseudo_shear_rate");
    if (given.size() > 1) t->fail(given[1], "give " + given[0] + " or " + given[1] + ", not both");
    if (given.empty()) {
      t->fail_table("a periodic domain needs mean_velocity, pressure_gradient, tube_velocity or pseudo_shear_rate "
                    "(mean_velocity = [0, 0, 0] for no imposed flow)");
    }
  } else {
    t->reject({"box", "mean_velocity", "pressure_gradient", "tube_velocity", "pseudo_shear_rate"},
              "kind = \"periodic\"");
    if (auto f = t->table("background_flow")) {
      d.background_flow.kind = f->choice<FlowKind>(
          "kind", FlowKind::none,
          {{"none", FlowKind::none}, {"shear", FlowKind::shear}, {"extensional", FlowKind::extensional}});
      if (d.background_flow.kind == FlowKind::none) {
        f->reject({"rate"}, "kind = \"shear\" or \"extensional\"");
      }
      d.background_flow.rate = f->real("rate", d.background_flow.rate, any_finite());
      f->finish();
    }
  }
  t->finish();
  return d;
}

// [vessel] segments = [{ from = [x, y, z], to = [x, y, z], diameter = d }, ...]; the geometry
// (junctions, overlaps, the box) is checked where the network is built.
std::vector<CaseSegment> read_segments(Table& t) {
  const toml::value* list = t.get("segments");
  if (!list) t.fail_table("segments = [{ from = [x, y, z], to = [x, y, z], diameter = d }, ...] is required for kind = \"network\"");
  const auto& a = t.to_array("segments", *list, 0, "an array of { from, to, diameter } tables");
  if (a.empty()) t.fail("segments", "the list is empty");
  std::vector<CaseSegment> segments;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string key = "segments[" + std::to_string(i) + "]";
    if (!a[i].is_table()) t.fail_value(a[i], key, "expected a table { from, to, diameter }, got " + type_name(a[i]));
    Table g = t.nested(a[i], key);
    CaseSegment segment;
    const auto from = g.vec3("from", any_finite()), to = g.vec3("to", any_finite());
    const auto diameter = g.optional_real("diameter", positive());
    if (!from || !to || !diameter) g.fail_table("from, to and diameter are required");
    segment.from = *from;
    segment.to = *to;
    segment.diameter = *diameter;
    g.finish();
    segments.push_back(segment);
  }
  return segments;
}

std::optional<CaseVessel> read_vessel(Table& top, const CaseDomain& d, const fs::path& base) {
  auto t = top.table("vessel");
  if (!t) return std::nullopt;
  if (d.kind != DomainKind::periodic) top.fail("vessel", "a vessel needs [domain] kind = \"periodic\"");
  CaseVessel v;
  v.kind = t->choice<VesselKind>("kind", VesselKind::tube,
                                 {{"tube", VesselKind::tube},
                                  {"constriction", VesselKind::constriction},
                                  {"bifurcation", VesselKind::bifurcation},
                                  {"file", VesselKind::file},
                                  {"network", VesselKind::network}});
  v.axis = t->choice<int>("axis", 2, {{"x", 0}, {"y", 1}, {"z", 2}});
  const double length = d.box[v.axis];
  const double cross = std::min(d.box[(v.axis + 1) % 3], d.box[(v.axis + 2) % 3]);
  const std::vector<std::string> constriction_keys{"depth", "width"};
  const std::vector<std::string> bifurcation_keys{"daughter_diameters", "angle_deg"};
  const std::vector<std::string> file_keys{"path", "scale"};

  if (v.kind == VesselKind::file) {
    t->reject({"diameter", "center"}, "kind = \"tube\", \"constriction\" or \"bifurcation\"");
    t->reject({"fillet_radius"}, "kind = \"bifurcation\" or \"network\"");
    t->reject(constriction_keys, "kind = \"constriction\"");
    t->reject(bifurcation_keys, "kind = \"bifurcation\"");
    const auto p = t->optional_text("path");
    if (!p) t->fail_table("path = \"FILE\" is required for kind = \"file\"");
    v.path = (base / *p).lexically_normal();
    std::string ext = v.path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext != ".msh" && ext != ".stl" && ext != ".step" && ext != ".stp" && ext != ".iges" && ext != ".igs") {
      t->fail("path", "\"" + *p + "\" is not a .msh, .stl, .step or .iges file");
    }
    if (!fs::is_regular_file(v.path)) t->fail("path", "no such file: " + v.path.string());
    v.scale = t->real("scale", v.scale, positive());
    v.element_size = t->real("element_size", v.element_size, open_closed(0, cross / 2));
    t->finish();
    return v;
  }

  if (v.kind == VesselKind::network) {
    t->reject({"diameter", "center"}, "kind = \"tube\", \"constriction\" or \"bifurcation\"");
    t->reject(constriction_keys, "kind = \"constriction\"");
    t->reject(bifurcation_keys, "kind = \"bifurcation\"");
    t->reject(file_keys, "kind = \"file\"");
    v.segments = read_segments(*t);
    v.element_size = t->real("element_size", v.element_size, open_closed(0, cross / 2));
    double narrowest = kInf;
    for (const CaseSegment& g : v.segments) narrowest = std::min(narrowest, 0.5 * g.diameter);
    v.fillet_radius = t->real("fillet_radius", 0.0, closed_open(0, narrowest));
    t->finish();
    return v;
  }

  t->reject(file_keys, "kind = \"file\"");
  t->reject({"segments"}, "kind = \"network\"");
  const auto diameter = t->optional_real("diameter", open(0, cross));
  if (!diameter) t->fail_table("diameter is required for kind = \"" + to_string(v.kind) + "\"");
  v.diameter = *diameter;
  v.element_size = t->real("element_size", v.element_size, open_closed(0, v.diameter / 2));
  if (v.kind != VesselKind::bifurcation) t->reject({"fillet_radius"}, "kind = \"bifurcation\" or \"network\"");
  if (v.kind == VesselKind::tube) {
    t->reject({"center"}, "kind = \"constriction\" or \"bifurcation\"");
    t->reject(constriction_keys, "kind = \"constriction\"");
    t->reject(bifurcation_keys, "kind = \"bifurcation\"");
  } else if (v.kind == VesselKind::constriction) {
    t->reject(bifurcation_keys, "kind = \"bifurcation\"");
    const auto depth = t->optional_real("depth", open(0, v.diameter));
    const auto width = t->optional_real("width", positive());
    if (!depth || !width) t->fail_table("depth and width are required for kind = \"constriction\"");
    v.depth = *depth;
    v.width = *width;
    v.center = t->real("center", length / 2, closed(0, length));
  } else {
    t->reject(constriction_keys, "kind = \"constriction\"");
    const double murray = v.diameter / std::cbrt(2.0);  // Murray's law: d^3 = d1^3 + d2^3
    v.daughter_diameters = {murray, murray};
    if (const toml::value* dd = t->get("daughter_diameters")) {
      const auto& a = t->to_array("daughter_diameters", *dd, 2, "an array of 2 numbers");
      for (int i = 0; i < 2; ++i) {
        v.daughter_diameters[i] = t->to_real("daughter_diameters", a[i], open_closed(0, v.diameter));
      }
    }
    v.angle_deg = t->real("angle_deg", 60.0, open(0, 180));
    const double smaller = 0.5 * std::min(v.daughter_diameters[0], v.daughter_diameters[1]);
    v.fillet_radius = t->real("fillet_radius", 0.0, closed_open(0, smaller));
    v.center = t->real("center", length / 2, open(0, length));
  }
  t->finish();
  return v;
}

CaseMembrane read_membrane(Table& cells) {
  CaseMembrane m;
  auto t = cells.table("membrane");
  if (!t) return m;
  m.law = t->choice<MembraneLawKind>("law", m.law,
                                 {{"skalak", MembraneLawKind::skalak},
                                  {"neo-hookean", MembraneLawKind::neo_hookean},
                                  {"hookean", MembraneLawKind::hookean}});
  m.shear_modulus = t->real("shear_modulus", m.shear_modulus, positive());
  if (m.law == MembraneLawKind::neo_hookean) {
    t->reject({"dilatation_modulus"}, "law = \"skalak\" or \"hookean\"");
  }
  m.dilatation_modulus = t->real("dilatation_modulus", m.dilatation_modulus, positive());
  m.bending_modulus = t->real("bending_modulus", m.bending_modulus, non_negative());
  t->finish();
  return m;
}

std::string vec3_text(const Vec3& x) {
  return "[" + number_text(x[0]) + ", " + number_text(x[1]) + ", " + number_text(x[2]) + "]";
}

std::optional<CaseCells> read_cells(Table& top, const CaseDomain& d, bool has_vessel) {
  auto t = top.table("cells");
  if (!t) return std::nullopt;
  CaseCells c;
  c.shape = t->choice<CellShape>("shape", c.shape,
                                 {{"rbc", CellShape::rbc},
                                  {"sphere", CellShape::sphere},
                                  {"ellipsoid", CellShape::ellipsoid}});
  if (c.shape == CellShape::ellipsoid) {
    c.semi_axes = t->vec3("semi_axes", positive()).value_or(c.semi_axes);
  } else {
    t->reject({"semi_axes"}, "shape = \"ellipsoid\"");
  }
  c.order = t->integer("order", c.order, 4, 128);
  c.dealias = t->integer("dealias", c.dealias, 1, 4);
  c.seed = t->integer("seed", c.seed, 0, std::numeric_limits<int>::max());
  c.narrow_start = t->choice<NarrowStartKind>("narrow_start", c.narrow_start,
                                          {{"stretched", NarrowStartKind::stretched}, {"parachute", NarrowStartKind::parachute}});
  c.count = t->optional_integer("count", 1, 1000000);
  c.hematocrit = t->optional_real("hematocrit", open_closed(0, 0.5));
  c.positions = t->vec3_list("positions", any_finite());
  c.orientations = t->vec3_list("orientations", any_finite());
  if (c.count && c.hematocrit) t->fail("hematocrit", "give count or hematocrit, not both");
  if (c.hematocrit && !has_vessel) {
    t->fail("hematocrit", "the tube hematocrit needs a [vessel] (use count without one)");
  }
  if (c.hematocrit && !c.positions.empty()) {
    t->fail("positions", "give positions or hematocrit, not both");
  }
  const int n = static_cast<int>(c.positions.size());
  if (!c.positions.empty()) {
    if (c.count && *c.count != n) {
      t->fail("count", std::to_string(*c.count) + " cells but " + std::to_string(n) + " positions");
    }
    c.count = n;
  }
  if (!c.count && !c.hematocrit) c.count = 1;
  if (d.kind == DomainKind::free && c.positions.empty()) {
    t->fail_table("cells in a free domain need positions (e.g. positions = [[0, 0, 0]])");
  }
  if (!c.orientations.empty()) {
    if (c.positions.empty()) t->fail("orientations", "orientations need positions");
    if (static_cast<int>(c.orientations.size()) != n) {
      t->fail("orientations", std::to_string(c.orientations.size()) + " orientations for " +
                                  std::to_string(n) + " positions");
    }
    for (std::size_t i = 0; i < c.orientations.size(); ++i) {
      const Vec3& o = c.orientations[i];
      if (std::hypot(o[0], o[1], o[2]) < 1e-12) {
        t->fail("orientations", "orientations[" + std::to_string(i) + "] is the zero vector");
      }
    }
  }
  if (d.kind == DomainKind::periodic) {
    for (std::size_t i = 0; i < c.positions.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        const double x = c.positions[i][k];
        if (!(x >= 0 && x < d.box[k])) {
          t->fail("positions", "positions[" + std::to_string(i) + "] = " + vec3_text(c.positions[i]) +
                                   " lies outside the box [0, " + number_text(d.box[0]) + ") x [0, " +
                                   number_text(d.box[1]) + ") x [0, " + number_text(d.box[2]) + ")");
        }
      }
    }
  }
  c.body_force = t->vec3("body_force", any_finite()).value_or(c.body_force);
  if (auto p = t->table("perturbation")) {
    CasePerturbation q;
    q.l = p->integer("l", q.l, 0, c.order - 1);
    q.m = p->integer("m", q.m, -q.l, q.l);
    q.amplitude = p->real("amplitude", q.amplitude, closed(-0.5, 0.5));
    p->finish();
    c.perturbation = q;
  }
  c.membrane = read_membrane(*t);
  t->finish();
  return c;
}

// Ranges as libsolver's Ewald sums accept them (spme/ewald_parameters.h, spme/bspline.h).
CaseEwald read_ewald(Table& top, const CaseDomain& d) {
  CaseEwald e;
  auto t = top.table("ewald");
  if (!t) return e;
  e.tolerance = t->real("tolerance", e.tolerance, closed(1e-10, 1e-3));
  e.alpha = t->optional_real("alpha", positive());
  const double longest = std::max({d.box[0], d.box[1], d.box[2]});
  e.cutoff = t->optional_real("cutoff", d.kind == DomainKind::periodic ? open_closed(0, 16 * longest) : positive());
  e.spline_order = t->optional_integer("spline_order", 4, 10);
  const int min_side = 2 * e.spline_order.value_or(4);
  e.grid = t->int_array<3>("grid", min_side, 4096);
  if (e.grid) {
    for (const int side : *e.grid) {
      if (side % 2 != 0) t->fail("grid", std::to_string(side) + " is odd (grid sides are even)");
    }
  }
  t->finish();
  return e;
}

CaseSolver read_solver(Table& top) {
  CaseSolver s;
  auto t = top.table("solver");
  if (!t) return s;
  s.gmres_tolerance = t->real("gmres_tolerance", s.gmres_tolerance, open(0, 1));
  s.max_iterations = t->integer("max_iterations", s.max_iterations, 1, 100000);
  s.patch_radial_points = t->optional_integer("patch_radial_points", 4, 64);
  s.memory_gib = t->optional_real("memory_gib", open_closed(0, 1e6));
  s.wall_preconditioner_block_nodes =
      t->integer("wall_preconditioner_block_nodes", s.wall_preconditioner_block_nodes, 1, 10000000);
  t->finish();
  return s;
}

CaseUnits read_units(Table& top) {
  CaseUnits u;
  auto t = top.table("units");
  if (!t) return u;
  u.length_um = t->real("length_um", u.length_um, open_closed(0, 1e6));
  u.rate_per_s = t->real("rate_per_s", u.rate_per_s, open_closed(0, 1e9));
  u.plasma_viscosity_mpas = t->real("plasma_viscosity_mpas", u.plasma_viscosity_mpas, open_closed(0, 1e6));
  t->finish();
  return u;
}

CaseTime read_time(Table& top) {
  CaseTime tm;
  auto t = top.table("time");
  if (!t) return tm;
  tm.end = t->real("end", tm.end, positive());
  if (const toml::value* dt = t->get("dt")) {
    if (!(dt->is_string() && dt->as_string().str == "auto")) {
      if (dt->is_string()) t->fail("dt", "\"" + dt->as_string().str + "\" is not allowed (a number or \"auto\")");
      tm.dt = t->to_real("dt", *dt, open_closed(0, tm.end));
    }
  }
  tm.dt_safety = t->real("dt_safety", tm.dt_safety, open_closed(0, 1));
  if (tm.dt) t->reject({"dt_safety"}, "dt = \"auto\"");
  tm.scheme = t->choice<TimeSchemeKind>("scheme", tm.scheme,
                                    {{"euler", TimeSchemeKind::euler}, {"ab2", TimeSchemeKind::ab2}});
  tm.collision_threshold = t->real("collision_threshold", tm.collision_threshold, closed(0, 0.5));
  tm.contact_range = t->real("contact_range", tm.contact_range, closed(0, 0.5));
  if (tm.contact_range > 0) {
    if (!t->has("contact_strength")) t->fail("contact_strength", "is needed with contact_range (the repulsion's traction scale)");
    tm.contact_strength = t->real("contact_strength", tm.contact_strength, open_closed(0, 1e9));
    if (tm.contact_range <= tm.collision_threshold)
      t->fail("contact_range", "must exceed collision_threshold (" + std::to_string(tm.collision_threshold) +
                                   "): the repulsion acts between h_s and its range");
  } else {
    t->reject({"contact_strength"}, "a contact_range above 0");
  }
  tm.volume_constraint = t->boolean("volume_constraint", tm.volume_constraint);
  t->finish();
  return tm;
}

CaseOutput read_output(Table& top, const fs::path& file) {
  CaseOutput o;
  o.dir = fs::path("out") / file.stem();
  auto t = top.table("output");
  if (!t) return o;
  if (auto dir = t->optional_text("dir")) {
    if (dir->empty()) t->fail("dir", "the output directory is empty");
    o.dir = *dir;
  }
  o.every = t->integer("every", o.every, 1, std::numeric_limits<int>::max());
  if (const toml::value* f = t->get("formats")) {
    const auto& a = t->to_array("formats", *f, 0, "an array of \"xdmf\" and \"vtk\"");
    o.xdmf = o.vtk = false;
    for (const auto& x : a) {
      const bool is_xdmf = x.is_string() && x.as_string().str == "xdmf";
      const bool is_vtk = x.is_string() && x.as_string().str == "vtk";
      if (!is_xdmf && !is_vtk) t->fail("formats", "an entry is not \"xdmf\" or \"vtk\"");
      bool& flag = is_xdmf ? o.xdmf : o.vtk;
      if (flag) t->fail("formats", "a format is listed twice");
      flag = true;
    }
  }
  o.render = t->boolean("render", o.render);
  o.render_every = t->integer("render_every", o.render_every, 0, std::numeric_limits<int>::max());
  o.render_field = t->choice<std::string>("render_field", o.render_field,
                                          {{"tension", "tension"}, {"J_S", "J_S"},
                                           {"velocity", "velocity"}, {"force", "force"},
                                           {"none", "none"}});
  o.render_view = t->choice<RenderView>("render_view", o.render_view,
                                        {{"side", RenderView::side}, {"end", RenderView::end},
                                         {"iso", RenderView::iso}});
  if (auto size = t->int_array<2>("render_size", 16, 8192)) o.render_size = *size;
  o.checkpoint_every = t->integer("checkpoint_every", o.checkpoint_every, 0, std::numeric_limits<int>::max());
  t->finish();
  return o;
}

Case read_root(const toml::value& root, const fs::path& file) {
  Case c;
  c.source.file = file;
  Context ctx(file, c.source);
  Table top(root, "", ctx);
  c.title = top.optional_text("title").value_or(file.stem().string());
  c.domain = read_domain(top);
  c.vessel = read_vessel(top, c.domain, file.parent_path());
  for (const auto& [key, given] : {std::pair{"tube_velocity", c.domain.tube_velocity.has_value()},
                                   std::pair{"pseudo_shear_rate", c.domain.pseudo_shear_rate.has_value()}}) {
    if (given && !(c.vessel && (c.vessel->kind == VesselKind::tube || c.vessel->kind == VesselKind::constriction ||
                                c.vessel->kind == VesselKind::bifurcation))) {
      ctx.fail(c.source.lines.at(std::string("domain.") + key), std::string("domain.") + key,
               "needs a [vessel] of kind \"tube\", \"constriction\" or \"bifurcation\" (the flow in its straight "
               "(parent) section sets <u>); use mean_velocity or pressure_gradient otherwise");
    }
  }
  c.cells = read_cells(top, c.domain, c.vessel.has_value());
  c.ewald = read_ewald(top, c.domain);
  c.solver = read_solver(top);
  c.time = read_time(top);
  c.output = read_output(top, file);
  c.units = read_units(top);
  top.finish();
  return c;
}

// The line and byte offset of the first byte that is not well-formed UTF-8 (no overlong forms,
// surrogates or code points beyond U+10FFFF), or line 0. TOML files are UTF-8; checked
// before toml11 sees the text, whose error paths for invalid UTF-8 in literal strings read
// past the end of its buffer (toml11 3.7.1, found by tests/io/fuzz).
std::pair<int, std::size_t> invalid_utf8(const std::string& text) {
  const auto* b = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  int line = 1;
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = b[i];
    std::size_t len = 0;
    unsigned char lo = 0x80, hi = 0xbf;  // allowed range of the second byte
    if (c < 0x80) {
      if (c == '\n') ++line;
      ++i;
      continue;
    } else if (c >= 0xc2 && c <= 0xdf) {
      len = 2;
    } else if (c >= 0xe0 && c <= 0xef) {
      len = 3;
      if (c == 0xe0) lo = 0xa0;
      if (c == 0xed) hi = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
      len = 4;
      if (c == 0xf0) lo = 0x90;
      if (c == 0xf4) hi = 0x8f;
    } else {
      return {line, i};
    }
    if (i + len > n || b[i + 1] < lo || b[i + 1] > hi) return {line, i};
    for (std::size_t k = 2; k < len; ++k) {
      if (b[i + k] < 0x80 || b[i + k] > 0xbf) return {line, i};
    }
    i += len;
  }
  return {0, 0};
}

// "[error] toml::parse_array: missing ..." -> "missing ...", then toml11's source excerpt.
std::string syntax_message(const std::string& what) {
  std::string first = what.substr(0, what.find('\n'));
  const std::string rest = what.size() > first.size() ? what.substr(first.size()) : "";
  if (first.rfind("[error] ", 0) == 0) first = first.substr(8);
  const auto colon = first.find(": ");
  if (first.rfind("toml::", 0) == 0 && colon != std::string::npos) first = first.substr(colon + 2);
  return first + rest;
}

}  // namespace

Case parse_case(const std::string& text, const fs::path& file) {
  if (const auto [line, byte] = invalid_utf8(text); line > 0) {
    throw CaseError(file.string() + ":" + std::to_string(line) + ": malformed TOML: not UTF-8 (byte " +
                    std::to_string(byte) + " of the file)");
  }
  toml::value root;
  try {
    std::istringstream in(text);
    root = toml::parse(in, file.string());
  } catch (const toml::exception& e) {
    const int line = static_cast<int>(e.location().line());
    throw CaseError(file.string() + (line > 0 ? ":" + std::to_string(line) : "") +
                    ": malformed TOML: " + syntax_message(e.what()));
  } catch (const std::exception& e) {
    throw CaseError(file.string() + ": malformed TOML: " + e.what());
  }
  return read_root(root, file);
}

Case read_case(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in || fs::is_directory(file)) throw CaseError(file.string() + ": cannot read the case file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_case(text.str(), file);
}

}  // namespace rbcflow
