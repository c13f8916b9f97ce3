// Scenario files: JSON text -> the validated plain structs of scenario.hpp.
// Every problem is reported as (JSON path, what was found, what was expected) so that a user
// can fix a scene from the message alone. Reading stops at the first problem. The strict
// JSON reading itself (unknown keys, types, messages) is json_reading.hpp, shared with study
// files.

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string_view>
#include <utility>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/kernels/any_kernel.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

namespace {

// The length of the valid UTF-8 sequence starting at text[i], or 0 when there is none.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto lead = static_cast<unsigned char>(text[i]);
  const std::size_t length = lead < 0x80         ? 1
                             : lead >> 5 == 0x6  ? 2
                             : lead >> 4 == 0xE  ? 3
                             : lead >> 3 == 0x1E ? 4
                                                 : 0;
  if (length == 0 || i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if (static_cast<unsigned char>(text[i + k]) >> 6 != 0x2) return 0;
  }
  return length;
}

std::string compose_message(const std::string& document, const std::string& path,
                            const std::string& found, const std::string& expected) {
  // The root has the empty pointer; "/" reads better in a message.
  return printable_line(document + " error at " + (path.empty() ? std::string("/") : path) +
                        ": found " + found + ", expected " + expected);
}

}  // namespace

std::string printable_line(std::string_view text) {
  static const char* const hex = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t length = utf8_length(text, i);
    // C0 and C1 controls (U+0080 to U+009F, two bytes from 0xC2) and DEL are escaped.
    const bool control = length == 1 ? c < 0x20 || c == 0x7F
                                     : c == 0xC2 && static_cast<unsigned char>(text[i + 1]) < 0xA0;
    if (length > 0 && !control) {
      out.append(text.substr(i, length));
      i += length;
      continue;
    }
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xF];
    }
    ++i;
  }
  return out;
}

ScenarioError::ScenarioError(std::string json_path, std::string found, std::string expected,
                             std::string document)
    : std::runtime_error(compose_message(document, json_path, found, expected)),
      json_path_(std::move(json_path)),
      found_(std::move(found)),
      expected_(std::move(expected)),
      document_(std::move(document)) {}

using namespace json_reading;

namespace {

// ---------------------------------------------------------------------------------------------
// Points and boxes

using json_reading::fmt;  // the overload for numbers, beside this one for points

std::string fmt(const Point& p) { return "(" + fmt(p[0]) + ", " + fmt(p[1]) + ")"; }

}  // namespace

std::array<double, 2> pair(const json& v, const std::string& path, const std::string& expected) {
  if (!v.is_array() || v.size() != 2) throw ScenarioError(path, describe(v), expected);
  return {finite_number(v[0], element_path(path, 0), expected),
          finite_number(v[1], element_path(path, 1), expected)};
}

namespace {

// `coordinates` names the pair, "x, y" for map points, "x, z" for a bed profile.
}  // namespace

std::vector<Point> points(const json& v, const std::string& path, std::size_t min_count,
                          const std::string& coordinates) {
  const std::string expected = "an array of at least " + std::to_string(min_count) + " [" +
                               coordinates + "] points (metres)";
  if (!v.is_array() || v.size() < min_count) throw ScenarioError(path, describe(v), expected);
  std::vector<Point> out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    out.push_back(
        pair(v[i], element_path(path, i), "an [" + coordinates + "] pair of numbers (metres)"));
  }
  return out;
}

namespace {

// Requires o[key] > o[lower_key] = lower; used for the x_min < x_max pairs of boxes.
void check_above(const Object& o, std::string_view key, double value, std::string_view lower_key,
                 double lower) {
  if (value > lower) return;
  throw ScenarioError(
      o.path(key), describe(*o.find(key)) + " with " + std::string(lower_key) + " = " + fmt(lower),
      "a number > " + std::string(lower_key) + " (metres)");
}

}  // namespace

Rectangle box(const Object& o) {
  const std::string expected = "a number (metres)";
  Rectangle r;
  r.x_min = number(o, "x_min", expected);
  r.x_max = number(o, "x_max", expected);
  r.y_min = number(o, "y_min", expected);
  r.y_max = number(o, "y_max", expected);
  check_above(o, "x_max", r.x_max, "x_min", r.x_min);
  check_above(o, "y_max", r.y_max, "y_min", r.y_min);
  return r;
}

const Names kBoxKeys = {"x_min", "x_max", "y_min", "y_max"};

namespace {

const std::string kBoxExpected = "an object with x_min, x_max, y_min, y_max (metres)";

}  // namespace

Rectangle read_box(const json& v, const std::string& path) {
  return box(Object(v, path, kBoxKeys, kBoxExpected));
}

namespace {

// ---------------------------------------------------------------------------------------------
// Geometry checks

double cross(const Point& o, const Point& a, const Point& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

int turn(const Point& o, const Point& a, const Point& b) {
  const double c = cross(o, a, b);
  return (c > 0.0) - (c < 0.0);
}

// r, known to be collinear with p and q, lies on the closed segment p-q.
bool within(const Point& p, const Point& q, const Point& r) {
  return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
         std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
}

// Closed segments a-b and c-d share at least one point (crossing, touching or overlapping).
bool segments_meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int s1 = turn(c, d, a), s2 = turn(c, d, b), s3 = turn(a, b, c), s4 = turn(a, b, d);
  if (s1 * s2 < 0 && s3 * s4 < 0) return true;
  return (s1 == 0 && within(c, d, a)) || (s2 == 0 && within(c, d, b)) ||
         (s3 == 0 && within(a, b, c)) || (s4 == 0 && within(a, b, d));
}

double signed_area(const std::vector<Point>& poly) {
  double twice = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point& a = poly[i];
    const Point& b = poly[(i + 1) % poly.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * twice;
}

}  // namespace

Rectangle bounding_box(const std::vector<Point>& pts) {
  Rectangle r{pts[0][0], pts[0][0], pts[0][1], pts[0][1]};
  for (const Point& p : pts) {
    r.x_min = std::min(r.x_min, p[0]);
    r.x_max = std::max(r.x_max, p[0]);
    r.y_min = std::min(r.y_min, p[1]);
    r.y_max = std::max(r.y_max, p[1]);
  }
  return r;
}

namespace {

// Consecutive points must differ; for a polygon the last one also precedes the first.
}  // namespace

void check_distinct_neighbours(const std::vector<Point>& pts, const std::string& path,
                               bool closed) {
  const std::size_t n = pts.size();
  const std::size_t pairs = closed ? n : n - 1;
  for (std::size_t i = 0; i < pairs; ++i) {
    const std::size_t next = (i + 1) % n;
    if (pts[i] != pts[next]) continue;
    throw ScenarioError(
        element_path(path, next),
        "the point " + fmt(pts[next]) + " again (same as point " + std::to_string(i) + ")",
        closed ? "a vertex different from the one before it (a polygon closes "
                 "itself: do not repeat the first vertex at the end)"
               : "a point different from the one before it");
  }
}

namespace {

// A simple polygon: no two edges meet except neighbours at their shared vertex.
void check_simple(const std::vector<Point>& poly, const std::string& path) {
  const std::string expected =
      "a simple polygon of non-zero area (no edge may cross, touch or overlap another)";
  const std::size_t n = poly.size();
  // Neighbouring edges always share a vertex; they only overlap when the outline turns back
  // on itself there, which the non-neighbour test below cannot see.
  for (std::size_t i = 0; i < n; ++i) {
    const Point& a = poly[(i + n - 1) % n];
    const Point& b = poly[i];
    const Point& c = poly[(i + 1) % n];
    const double dot = (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]);
    if (cross(a, b, c) == 0.0 && dot < 0.0) {
      throw ScenarioError(element_path(path, i), "the outline turning back on itself at " + fmt(b),
                          expected);
    }
  }
  // Non-neighbour edges, swept in order of their left ends so that only edges whose boxes
  // overlap are tested: a coastline of 10^5 vertices would take minutes pair by pair. The
  // pair reported is the first in edge order, as a plain double loop would find it.
  struct EdgeBox {
    double x_min, x_max, y_min, y_max;
    std::size_t index;
  };
  std::vector<EdgeBox> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point &a = poly[i], &b = poly[(i + 1) % n];
    boxes[i] = {std::min(a[0], b[0]), std::max(a[0], b[0]), std::min(a[1], b[1]),
                std::max(a[1], b[1]), i};
  }
  std::sort(boxes.begin(), boxes.end(),
            [](const EdgeBox& l, const EdgeBox& r) { return l.x_min < r.x_min; });
  std::optional<std::pair<std::size_t, std::size_t>> first;
  for (std::size_t s = 0; s < n; ++s) {
    for (std::size_t t = s + 1; t < n && boxes[t].x_min <= boxes[s].x_max; ++t) {
      if (boxes[t].y_min > boxes[s].y_max || boxes[s].y_min > boxes[t].y_max) continue;
      const std::size_t i = std::min(boxes[s].index, boxes[t].index);
      const std::size_t j = std::max(boxes[s].index, boxes[t].index);
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours share a vertex
      if (!segments_meet(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) continue;
      if (!first || std::make_pair(i, j) < *first) first = std::make_pair(i, j);
    }
  }
  if (first) {
    const auto [i, j] = *first;
    const Point &a = poly[i], &b = poly[(i + 1) % n], &c = poly[j], &d = poly[(j + 1) % n];
    throw ScenarioError(path,
                        "edge " + std::to_string(i) + " " + fmt(a) + "-" + fmt(b) + " and edge " +
                            std::to_string(j) + " " + fmt(c) + "-" + fmt(d) + " intersecting",
                        expected);
  }
  // Guards against outlines so thin that rounding hid their degeneracy from the tests above.
  const Rectangle bb = bounding_box(poly);
  const double w = bb.x_max - bb.x_min, h = bb.y_max - bb.y_min;
  if (std::abs(signed_area(poly)) <= 1e-12 * (w * w + h * h)) {
    throw ScenarioError(path, "a polygon of zero area", expected);
  }
}

}  // namespace

std::vector<Point> read_polygon(const json& v, const std::string& path) {
  std::vector<Point> poly = points(v, path, 3);
  check_distinct_neighbours(poly, path, true);
  check_simple(poly, path);
  return poly;
}

std::vector<Point> corners(const Rectangle& r) {
  return {{r.x_min, r.y_min}, {r.x_max, r.y_min}, {r.x_max, r.y_max}, {r.x_min, r.y_max}};
}

std::string describe_box(const Rectangle& r) {
  std::string text = "[";
  for (const auto& part : {fmt(r.x_min), std::string(", "), fmt(r.x_max), std::string("] x ["),
                           fmt(r.y_min), std::string(", "), fmt(r.y_max), std::string("]")}) {
    text += part;
  }
  return text;
}

namespace {

// Points must lie inside the domain: water outside it would be removed at once, and an inflow
// line or gauge outside it would see no water. `vertex_paths` points errors at the offending
// vertex rather than at the whole shape; `what` names the thing ("water lying").
}  // namespace

void check_inside(const std::vector<Point>& poly, const Rectangle& domain, const std::string& path,
                  bool vertex_paths, const std::string& what) {
  // Relative slack, so that coordinates in the millions (projected maps) are not failed by
  // a rounding error, and at least 1e-9 m elsewhere.
  const double scale = std::max({1.0, std::abs(domain.x_min), std::abs(domain.x_max),
                                 std::abs(domain.y_min), std::abs(domain.y_max)});
  const double slack = 1e-9 * scale;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point& p = poly[i];
    const bool inside = p[0] >= domain.x_min - slack && p[0] <= domain.x_max + slack &&
                        p[1] >= domain.y_min - slack && p[1] <= domain.y_max + slack;
    if (inside) continue;
    const std::string which =
        vertex_paths || poly.size() == 1 ? "" : " (vertex " + std::to_string(i) + ")";
    throw ScenarioError(
        vertex_paths ? element_path(path, i) : path,
        "the point " + fmt(p) + which + " outside the domain " + describe_box(domain),
        what + " inside the domain");
  }
}

namespace {

// ---------------------------------------------------------------------------------------------
// Sections of the scene

swe::Settings read_numerics(const json* v, double gravity, std::optional<double>& eddy_viscosity,
                            std::optional<double>& shock_viscosity) {
  const Object o(
      v ? *v : empty_object(), "/numerics",
      {"scheme", "cfl", "alpha_e", "max_area_ratio", "gradient", "kappa", "kernel", "dissipation",
       "shifting", "bed_term", "min_time_step", "eddy_viscosity", "shock_viscosity"},
      "an object");
  swe::Settings s;
  s.gravity_m_s2 = gravity;
  const bool seed = choice(o, "scheme", {"conservative", "seed"},
                           s.scheme == swe::SchemeKind::seed ? "seed" : "conservative") == "seed";
  s.scheme = seed ? swe::SchemeKind::seed : swe::SchemeKind::conservative;
  // Each scheme's own knobs are refused under the other, where they would be silently ignored.
  const auto only_under = [&](std::string_view key, bool allowed, std::string_view scheme) {
    if (allowed || o.find(key) == nullptr) return;
    throw ScenarioError(o.path(key),
                        "\"" + std::string(key) + "\" under the " +
                            std::string(seed ? "seed" : "conservative") + " scheme",
                        "no \"" + std::string(key) + "\" here (it sets the " + std::string(scheme) +
                            " scheme; see \"scheme\")");
  };
  for (const auto* key : {"alpha_e", "gradient"}) only_under(key, seed, "seed");
  for (const auto* key : {"kappa", "kernel", "dissipation", "shifting", "bed_term"})
    only_under(key, !seed, "conservative");
  s.cfl = bounded(o, "cfl", 0.0, true, 1.0, "the Courant number", s.cfl);
  // Below 1 the support holds too few neighbours for a stable gradient; above 3 the smoothing
  // is so wide that the answer no longer resolves the flow. Either is surely a mistake.
  s.alpha_e = bounded(o, "alpha_e", 1.0, false, 3.0,
                      "support radius r_e = alpha_e sqrt(A_max), in particle sizes", s.alpha_e);
  // The same bounds for h = kappa sqrt(A) (support 2 h): 1 puts 12 neighbours in the support,
  // 2.5 some 80.
  s.kappa = bounded(o, "kappa", 1.0, false, 2.5,
                    "kernel radius h = kappa sqrt(A), in particle sizes", s.kappa);
  const std::string_view kernel =
      choice(o, "kernel", {"cubic-spline", "spiky", "wendland-c2"}, "cubic-spline");
  s.kernel = kernel == "spiky"         ? swe::KernelShape::spiky
             : kernel == "wendland-c2" ? swe::KernelShape::wendland_c2
                                       : swe::KernelShape::cubic_spline;
  // 0 switches it off; above 2 it smears a bore over many particles: surely a mistake.
  s.dissipation = in_range(o, "dissipation", 0.0, false, 2.0, false,
                           "the pairwise dissipation coefficient alpha", s.dissipation);
  // 0 switches it off; above 10 a particle would be shifted by more than its velocity moves
  // it, surely a mistake.
  s.shifting = in_range(o, "shifting", 0.0, false, 10.0, false,
                        "the particle shifting coefficient beta", s.shifting);
  s.bed_term = choice(o, "bed_term", {"point", "balanced"}, "balanced") == "point"
                   ? swe::BedTerm::point
                   : swe::BedTerm::balanced;
  // Below 1 the bound would cut the areas of water that has merely thinned a little.
  // Absent: the scheme's own default (swe::Settings::area_ratio_cap()).
  if (o.find("max_area_ratio") != nullptr) {
    s.max_area_ratio = bounded(o, "max_area_ratio", 1.0, false, 100.0,
                               "the largest area a kernel radius follows, in multiples of A_0",
                               s.area_ratio_cap());
  }
  const std::string_view gradient = choice(o, "gradient", {"mps", "summation"}, "mps");
  s.gradient =
      gradient == "summation" ? swe::GradientVariant::summation : swe::GradientVariant::mps;
  s.min_time_step_s = positive(o, "min_time_step", kSeconds, s.min_time_step_s);
  // The other scheme's knobs were read for their defaults; the scene as read has none of them.
  for (const auto* key :
       seed ? std::vector<const char*>{"kappa", "kernel", "dissipation", "shifting", "bed_term"}
            : std::vector<const char*>{"alpha_e", "gradient"}) {
    DefaultsRecord::drop(o.path(key));
  }
  if (o.find("eddy_viscosity") != nullptr) {
    eddy_viscosity = positive(o, "eddy_viscosity", "m^2/s");
  }
  if (o.find("shock_viscosity") != nullptr) {
    // Monaghan's alpha: above 2 it smears a shock over many particles; surely a mistake.
    shock_viscosity =
        bounded(o, "shock_viscosity", 0.0, true, 2.0, "the shock viscosity coefficient alpha", 0.0);
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Files named by the scene

// A file the scene names, resolved against the scenario's folder. A GDAL dataset name that
// wraps a file, DRIVER:"file"[:rest] such as NETCDF:"dem.nc":elevation, has its file resolved
// and the rest kept.
std::filesystem::path resolve_file(const std::string& text, const std::filesystem::path& base_dir) {
  const auto resolve = [&](const std::string& name) {
    std::filesystem::path p(name);
    if (p.is_relative()) p = base_dir / p;
    return std::filesystem::absolute(p).lexically_normal();
  };
  if (const auto wrapped = io::split_dataset_name(text)) {
    return wrapped->driver + ":\"" + resolve(wrapped->file).string() + "\"" + wrapped->rest;
  }
  return resolve(text);
}

// o[key], a required non-empty string naming a file; `what` says what the file holds.
}  // namespace

std::filesystem::path file_path(const Object& o, std::string_view key, const std::string& what,
                                const std::filesystem::path& base_dir) {
  const std::string expected = "a path to " + what + " (relative to the scenario's folder)";
  const json* v = o.find(key);
  if (v == nullptr) throw ScenarioError(o.path(key), kMissing, expected);
  if (!v->is_string() || v->get_ref<const std::string&>().empty()) {
    throw ScenarioError(o.path(key), describe(*v), expected);
  }
  return resolve_file(v->get<std::string>(), base_dir);
}

namespace {

// o["crs"], the CRS a raster is warped to; empty when not given. Whether GDAL knows it is
// found out when the raster is read.
}  // namespace

std::string crs_text(const Object& o) {
  const std::string expected = "a projected CRS in metres, such as \"EPSG:32616\"";
  const auto crs = optional_string(o, "crs", expected);
  if (crs && crs->empty()) throw ScenarioError(o.path("crs"), describe(*o.find("crs")), expected);
  return crs.value_or("");
}

// "both "a" and "b"" or "all of "a", "b" and "c"", for keys that exclude each other.
std::string several(const std::vector<std::string_view>& keys) {
  if (keys.size() == 2) return "both " + literal(keys[0]) + " and " + literal(keys[1]);
  std::string out = "all of ";
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (i > 0) out += i + 1 == keys.size() ? " and " : ", ";
    out += literal(keys[i]);
  }
  return out;
}

namespace {

Wall read_wall(const json& v, const std::string& path) {
  const Object o(v, path, {"polyline", "condition"},
                 "an object with a \"polyline\" and optionally a \"condition\"");
  Wall wall;
  const json* line = o.find("polyline");
  if (line == nullptr) {
    throw ScenarioError(o.path("polyline"), kMissing,
                        "an array of at least 2 [x, y] points (metres)");
  }
  wall.polyline = points(*line, o.path("polyline"), 2);
  check_distinct_neighbours(wall.polyline, o.path("polyline"), false);
  const std::string_view condition = choice(o, "condition", {"slip", "no_slip"}, "slip");
  wall.condition = condition == "no_slip" ? WallCondition::no_slip : WallCondition::slip;
  return wall;
}

std::vector<Wall> read_walls(const json* v) {
  if (v == nullptr) return {};
  const std::string path = "/walls";
  if (!v->is_array()) throw ScenarioError(path, describe(*v), "an array of walls");
  std::vector<Wall> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    out.push_back(read_wall((*v)[i], element_path(path, i)));
  }
  return out;
}

BedSpec read_bed(const json* v, const std::filesystem::path& base_dir) {
  if (v == nullptr) return {};
  const std::string path = "/bed";
  const std::string one_kind = "exactly one of \"plane\", \"profile_x\" or \"raster\"";
  const Object o(*v, path, {"plane", "profile_x", "raster", "crs", "refinement"},
                 "an object with " + one_kind);
  std::vector<std::string_view> kinds;
  for (std::string_view key : {"plane", "profile_x", "raster"}) {
    if (o.find(key) != nullptr) kinds.push_back(key);
  }
  if (kinds.empty()) {
    throw ScenarioError(path, "none of \"plane\", \"profile_x\" or \"raster\"", one_kind);
  }
  if (kinds.size() > 1) throw ScenarioError(path, several(kinds), one_kind);
  for (std::string_view key : {"crs", "refinement"}) {
    if (kinds.front() != "raster" && o.find(key) != nullptr) {
      throw ScenarioError(
          o.path(key),
          "a \"" + std::string(key) + "\" with a " + std::string(kinds.front()) + " bed",
          "no \"" + std::string(key) + "\" here (it goes with a \"raster\" bed)");
    }
  }
  if (kinds.front() == "raster") {
    RasterBedSpec spec{RasterSpec{
        file_path(o, "raster", "a raster of bed elevations (metres)", base_dir), crs_text(o)}};
    spec.refinement =
        whole_number(o, "refinement", 1, 16, "fine cells across each warped cell of the bed",
                     RasterBedSpec::kDefaultBedRefinement);
    return spec;
  }
  if (const json* plane = o.find("plane")) {
    const Object po(*plane, o.path("plane"), {"elevation", "slope", "origin"},
                    "an object with elevation, slope and origin");
    PlaneBedSpec spec;
    spec.elevation_m = number(po, "elevation", "a number (metres)", 0.0);
    if (const json* slope = po.find("slope")) {
      spec.slope = pair(*slope, po.path("slope"), "a [dz/dx, dz/dy] pair of numbers (m/m)");
    }
    if (const json* origin = po.find("origin")) {
      spec.origin_m = pair(*origin, po.path("origin"), "an [x, y] pair of numbers (metres)");
    }
    return spec;
  }
  ProfileBedSpec spec;
  spec.points = points(*o.find("profile_x"), o.path("profile_x"), 2, "x, z");
  for (std::size_t i = 1; i < spec.points.size(); ++i) {
    if (!(spec.points[i][0] > spec.points[i - 1][0])) {
      throw ScenarioError(element_path(o.path("profile_x"), i), "x = " + fmt(spec.points[i][0]),
                          "x greater than the previous point's " + fmt(spec.points[i - 1][0]) +
                              " ([x, z] points with x strictly increasing)");
    }
  }
  return spec;
}

std::optional<splitting::SplittingSettings> read_splitting(const json* v) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, "/splitting", {"threshold", "alpha_s", "max_particles", "axis", "min_depth"},
                 "an object (empty for the defaults)");
  splitting::SplittingSettings s;
  // A threshold at or below 1 splits particles that have not grown; above 4 the tip is
  // long gone before a split. alpha_s beyond 1 places daughters beyond the parent's size.
  s.area_ratio_threshold =
      bounded(o, "threshold", 1.0, true, 4.0, "the area ratio A/A_0 that triggers a split",
              s.area_ratio_threshold);
  s.alpha_s = bounded(o, "alpha_s", 0.0, true, 1.0,
                      "the daughters' separation in particle sizes (eq 10)", s.alpha_s);
  const double cap = number(o, "max_particles", "a whole number >= 0 (0: no cap)", 0.0);
  if (cap < 0.0 || cap != std::floor(cap) || cap > 4e9) {
    throw ScenarioError(o.path("max_particles"), describe(*o.find("max_particles")),
                        "a whole number from 0 (no cap) to 4e9");
  }
  s.max_particles = static_cast<std::size_t>(cap);
  const std::string_view axis = choice(o, "axis", {"minor", "major"}, "minor");
  s.axis = axis == "major" ? splitting::SplitAxis::major : splitting::SplitAxis::minor;
  s.min_depth_m = non_negative(o, "min_depth", kMetres, s.min_depth_m);
  return s;
}

std::optional<splitting::MergingSettings> read_merging(
    const json* v, const std::optional<splitting::SplittingSettings>& split) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, "/merging", {"threshold"}, "an object (empty for the defaults)");
  splitting::MergingSettings s;
  // Two particles just under the threshold merge into one of twice its area: with splitting,
  // that must stay below the splitting threshold, or a merged particle is split at once.
  const bool splits = split.has_value();
  s.area_ratio_threshold = in_range(
      o, "threshold", 0.0, true, splits ? 0.5 * split->area_ratio_threshold : 1.0, splits,
      splits ? "the area ratio A/A_0 below which particles merge, below half the splitting "
               "threshold, or merged particles would split again at once"
             : "the area ratio A/A_0 below which particles merge",
      s.area_ratio_threshold);
  return s;
}

// without one, the rasters that name a CRS must name the same, for the scene has one CRS.
void check_crs_keys(const Scenario& s) {
  std::vector<std::pair<std::string, std::string>> given;  // (JSON path, CRS)
  if (s.manning_n) {
    const auto* map = std::get_if<RasterSpec>(&*s.manning_n);
    if (map && !map->crs.empty()) given.emplace_back("/friction/crs", map->crs);
    const auto* land_use = std::get_if<LandUseSpec>(&*s.manning_n);
    if (land_use && !land_use->raster.crs.empty()) {
      given.emplace_back("/friction/crs", land_use->raster.crs);
    }
  }
  for (std::size_t i = 0; i < s.water.size(); ++i) {
    const auto* depth = std::get_if<DepthRaster>(&s.water[i].depth);
    if (depth && !depth->raster.crs.empty()) {
      given.emplace_back(member_path(element_path("/water", i), "crs"), depth->raster.crs);
    }
  }
  const bool raster_bed = std::holds_alternative<RasterBedSpec>(s.bed);
  for (const auto& [path, crs] : given) {
    if (raster_bed) {
      throw ScenarioError(path, "a \"crs\" in a scene with a raster bed",
                          "no \"crs\" here (every raster is warped to the bed's CRS; set that "
                          "with bed.crs)");
    }
    if (crs != given.front().second) {
      throw ScenarioError(
          path,
          literal(crs) + " while " + given.front().first + " is " + literal(given.front().second),
          "the same CRS for every raster (the scene has one CRS)");
    }
  }
}

}  // namespace

void check_within_domain(const Scenario& scene, const Rectangle& domain) {
  for (std::size_t i = 0; i < scene.water.size(); ++i) {
    const auto& polygon = scene.water[i].polygon;
    if (!polygon.empty()) check_inside(polygon, domain, element_path("/water", i), false);
    if (const auto* wave = std::get_if<SolitaryWaveStart>(&scene.water[i].displacement)) {
      check_inside({wave->crest_m}, domain,
                   member_path(member_path(element_path("/water", i), "solitary_wave"), "crest"),
                   false, "a wave's crest point");
    }
  }
  if (scene.fault_source) {
    const auto& planes = scene.fault_source->planes;
    for (std::size_t i = 0; i < planes.size(); ++i) {
      if (planes[i].longitude_latitude) continue;  // placed, and checked, once projected
      check_inside({planes[i].plane.top_centre_m}, domain, element_path("/fault_source/planes", i),
                   false, "a fault plane's top edge midpoint lying");
    }
  }
  for (std::size_t i = 0; i < scene.inflows.size(); ++i) {
    const auto& line = scene.inflows[i].line;
    check_inside({line[0], line[1]}, domain, member_path(element_path("/inflow", i), "line"), true,
                 "an inflow line lying");
  }
  for (std::size_t i = 0; i < scene.sea_boundaries.size(); ++i) {
    const auto& line = scene.sea_boundaries[i].line;
    check_inside({line[0], line[1]}, domain,
                 member_path(element_path("/sea_boundaries", i), "line"), true,
                 "a sea boundary lying");
  }
  for (std::size_t i = 0; i < scene.output.gauges.size(); ++i) {
    check_inside({scene.output.gauges[i].position_m}, domain, element_path("/output/gauges", i),
                 false, "a gauge");
  }
  const GridSpec& grid = scene.output.grid;
  if (grid.spacing_m && !grid.bounds) {
    check_grid_cells(*grid.spacing_m, domain, "/output/grid/spacing");
  }
}

Scenario parse(const std::string& text, const std::filesystem::path& base_dir,
               const std::string& default_name) {
  const json root = parse_json(text);
  const DefaultsRecord as_read(root);
  const Object o(
      root, "", {"name",      "description",  "gravity",        "end_time", "numerics", "model",
                 "dimension", "ns",           "domain",         "water",    "walls",    "buildings",
                 "bed",       "friction",     "splitting",      "merging",  "inflow",   "rain",
                 "outflow",   "fault_source", "sea_boundaries", "output"},
      "a JSON object describing the scene");
  Scenario s;
  s.name = optional_string(o, "name", "a non-empty string").value_or(default_name);
  if (s.name.empty()) {
    throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
  }
  s.description = optional_string(o, "description", "a string").value_or("");

  const double gravity = positive(o, "gravity", "m/s^2", swe::Settings{}.gravity_m_s2);
  s.end_time_s = positive(o, "end_time", kSeconds);
  s.numerics = read_numerics(o.find("numerics"), gravity, s.eddy_viscosity_m2_s, s.shock_viscosity);
  read_model(o, gravity, s);

  // The bed comes first: a raster bed may give the domain, and water filled to a level needs
  // a bed to fill.
  s.bed = read_bed(o.find("bed"), base_dir);
  std::optional<Rectangle> domain;
  if (const json* given = o.find("domain")) {
    domain = read_box(*given, o.path("domain"));
    s.domain = *domain;
  } else if (std::holds_alternative<RasterBedSpec>(s.bed)) {
    s.domain_from_bed = true;  // checked against the water, inflows and gauges by build
  } else {
    throw ScenarioError(o.path("domain"), kMissing,
                        kBoxExpected +
                            "; only a raster bed, whose extent it then is, lets it be "
                            "left out");
  }

  const bool has_bed = !std::holds_alternative<std::monostate>(s.bed);
  // Model ns fills its tank on the "ns" lattice; a water body's own spacing is then optional.
  const double default_spacing_m = s.model == Model::ns ? s.ns->settings.spacing_m : 0.0;
  s.water =
      read_waters(o.find("water"), domain, has_bed, base_dir, default_spacing_m, s.numerics.scheme);
  default_tank_height(s);
  s.walls = read_walls(o.find("walls"));
  s.buildings = read_buildings(o.find("buildings"), base_dir);
  s.manning_n = read_friction(o.find("friction"), base_dir);
  s.splitting = read_splitting(o.find("splitting"));
  s.merging = read_merging(o.find("merging"), s.splitting);
  s.inflows = read_inflows(o.find("inflow"), s.water, base_dir);
  s.rain = read_rain(o.find("rain"), s.water, s.inflows, base_dir);
  if (s.water.empty() && s.inflows.empty() && s.rain.empty()) {
    const json* water = o.find("water");
    throw ScenarioError(o.path("water"), water ? describe(*water) : kMissing,
                        "a non-empty array of water bodies, or an \"inflow\" or \"rain\" to "
                        "bring water in");
  }
  s.outflows = read_outflows(o.find("outflow"));
  s.fault_source = read_fault_source(o.find("fault_source"));
  s.sea_boundaries = read_sea_boundaries(o.find("sea_boundaries"), s.water, base_dir);
  if (!s.sea_boundaries.empty() && s.numerics.scheme == swe::SchemeKind::seed) {
    // The boundary's water continues the lattice as the conservative scheme sums it.
    throw ScenarioError("/sea_boundaries", "sea boundaries under the seed scheme",
                        "the conservative scheme (the default) for a scene with sea boundaries");
  }
  check_crs_keys(s);
  s.output = read_output(o.find("output"), s, base_dir);
  if (domain) check_within_domain(s, *domain);
  if (s.model == Model::ns) check_ns_scene(s);
  s.as_read_json = as_read.document().dump(2);
  return s;
}

Scenario load(const std::filesystem::path& file) {
  const std::string text = read_text_file(file, "a readable scenario JSON file");
  const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
  const std::filesystem::path folder = absolute.parent_path();
  // A case kept as <case>/scenario.json is named after its folder; any other file after itself.
  const std::string name = absolute.filename() == "scenario.json" ? folder.filename().string()
                                                                  : absolute.stem().string();
  return parse(text, folder, name.empty() ? "scenario" : name);
}

}  // namespace swemps::scenario
