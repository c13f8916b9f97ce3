// Scenario files: JSON text -> the validated plain structs of scenario.hpp.
// Every problem is reported as (JSON path, what was found, what was expected) so that a user
// can fix a scene from the message alone. Reading stops at the first problem.

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

namespace {

std::string compose_message(const std::string& path, const std::string& found,
                            const std::string& expected) {
  // The root has the empty pointer; "/" reads better in a message.
  return "scenario error at " + (path.empty() ? std::string("/") : path) + ": found " + found +
         ", expected " + expected;
}

}  // namespace

ScenarioError::ScenarioError(std::string json_path, std::string found, std::string expected)
    : std::runtime_error(compose_message(json_path, found, expected)),
      json_path_(std::move(json_path)),
      found_(std::move(found)),
      expected_(std::move(expected)) {}

namespace {

using json = nlohmann::json;
using Names = std::vector<std::string_view>;

const std::string kMissing = "nothing (key missing)";
const std::string kMetres = "metres";
const std::string kSeconds = "seconds";

// An interval-generated output list longer than this is surely a typo in "interval".
constexpr double kMaxOutputTimes = 1e6;
// Each written grid field of this many cells takes gigabytes; a finer grid is surely a typo,
// better reported here than by the allocator.
constexpr double kMaxGridCells = 1e9;

// ---------------------------------------------------------------------------------------------
// Text helpers

std::string fmt(double v) {
  std::ostringstream s;
  s << std::setprecision(12) << v;
  return s.str();
}

std::string fmt(const Point& p) { return "(" + fmt(p[0]) + ", " + fmt(p[1]) + ")"; }

// A JSON string literal; invalid UTF-8 is replaced rather than thrown on, since it goes into
// an error message that must always be produced.
std::string literal(std::string_view s) {
  return json(std::string(s)).dump(-1, ' ', false, json::error_handler_t::replace);
}

// What a value is, in words, for the "found" part of an error.
std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "a string " + literal(s);
    }
    case json::value_t::array:
      if (v.empty()) return "an empty array";
      return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
    case json::value_t::object: return v.empty() ? "an empty object" : "an object";
    default: return v.dump();
  }
}

// JSON-pointer paths (RFC 6901 escapes "~" and "/" inside keys).
std::string member_path(const std::string& parent, std::string_view key) {
  std::string out = parent + "/";
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::string element_path(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

std::string join(const Names& names, bool quote) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += ", ";
    out += quote ? literal(names[i]) : std::string(names[i]);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Suggestions for misspelt keys and values

std::string lowered(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Optimal-string-alignment distance: insertions, deletions, substitutions and swaps of
// neighbours, so the common typing slip "dpeth" is one edit from "depth". Case is ignored.
std::size_t edit_distance(std::string_view a_in, std::string_view b_in) {
  const std::string a = lowered(a_in), b = lowered(b_in);
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

// " (did you mean "x"?)" when one of `choices` is close to `word`, else "".
std::string did_you_mean(std::string_view word, const Names& choices) {
  std::optional<std::string_view> best;
  std::size_t best_distance = 0;
  for (std::string_view c : choices) {
    const std::size_t d = edit_distance(word, c);
    if (!best || d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  // Short words tolerate two edits, longer ones a third of their length.
  const std::size_t tolerance = std::max<std::size_t>(2, word.size() / 3);
  if (!best || best_distance > tolerance) return "";
  return " (did you mean " + literal(*best) + "?)";
}

// ---------------------------------------------------------------------------------------------
// Reading values

// A JSON object of the scene with a fixed set of allowed keys: an unknown key is an error,
// so a typo never silently falls back to a default.
class Object {
 public:
  Object(const json& value, std::string path, Names keys, const std::string& expected)
      : value_(value), path_(std::move(path)), keys_(std::move(keys)) {
    if (!value_.is_object()) throw ScenarioError(path_, describe(value_), expected);
    for (auto it = value_.begin(); it != value_.end(); ++it) {
      if (std::find(keys_.begin(), keys_.end(), it.key()) == keys_.end()) {
        throw ScenarioError(
            this->path(it.key()), "an unknown key " + literal(it.key()),
            "one of the keys " + join(keys_, false) + did_you_mean(it.key(), keys_));
      }
    }
  }

  const json* find(std::string_view key) const {
    const auto it = value_.find(std::string(key));
    return it == value_.end() ? nullptr : &*it;
  }
  std::string path(std::string_view key) const { return member_path(path_, key); }
  const std::string& path() const { return path_; }

 private:
  const json& value_;
  std::string path_;
  Names keys_;
};

const json& empty_object() {
  static const json empty = json::object();
  return empty;
}

double finite_number(const json& v, const std::string& path, const std::string& expected) {
  if (!v.is_number()) throw ScenarioError(path, describe(v), expected);
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw ScenarioError(path, describe(v), expected);
  return x;
}

// o[key] as a finite number; a missing key gives `fallback`, or an error when there is none.
double number(const Object& o, std::string_view key, const std::string& expected,
              std::optional<double> fallback = std::nullopt) {
  const json* v = o.find(key);
  if (v == nullptr) {
    if (fallback) return *fallback;
    throw ScenarioError(o.path(key), kMissing, expected);
  }
  return finite_number(*v, o.path(key), expected);
}

double positive(const Object& o, std::string_view key, const std::string& unit,
                std::optional<double> fallback = std::nullopt) {
  const std::string expected = "a number > 0 (" + unit + ")";
  const double x = number(o, key, expected, fallback);
  if (!(x > 0.0)) throw ScenarioError(o.path(key), describe(*o.find(key)), expected);
  return x;
}

// A number within [low, high] (the lower end excluded when `open_low`).
double bounded(const Object& o, std::string_view key, double low, bool open_low, double high,
               const std::string& meaning, double fallback) {
  const std::string expected = "a number in " + std::string(open_low ? "(" : "[") + fmt(low) +
                               ", " + fmt(high) + "] (" + meaning + ")";
  const double x = number(o, key, expected, fallback);
  const bool above_low = open_low ? x > low : x >= low;
  if (!above_low || x > high) throw ScenarioError(o.path(key), describe(*o.find(key)), expected);
  return x;
}

std::optional<std::string> optional_string(const Object& o, std::string_view key,
                                           const std::string& expected) {
  const json* v = o.find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_string()) throw ScenarioError(o.path(key), describe(*v), expected);
  return v->get<std::string>();
}

// One of a fixed set of words; a near miss gets a suggestion.
std::string_view choice(const Object& o, std::string_view key, const Names& choices,
                        std::string_view fallback) {
  const std::string expected = "one of " + join(choices, true);
  const json* v = o.find(key);
  if (v == nullptr) return fallback;
  if (!v->is_string()) throw ScenarioError(o.path(key), describe(*v), expected);
  const auto& word = v->get_ref<const std::string&>();
  for (std::string_view c : choices) {
    if (c == word) return c;
  }
  throw ScenarioError(o.path(key), describe(*v), expected + did_you_mean(word, choices));
}

bool optional_bool(const Object& o, std::string_view key, bool fallback) {
  const json* v = o.find(key);
  if (v == nullptr) return fallback;
  if (!v->is_boolean()) throw ScenarioError(o.path(key), describe(*v), "true or false");
  return v->get<bool>();
}

std::array<double, 2> pair(const json& v, const std::string& path, const std::string& expected) {
  if (!v.is_array() || v.size() != 2) throw ScenarioError(path, describe(v), expected);
  return {finite_number(v[0], element_path(path, 0), expected),
          finite_number(v[1], element_path(path, 1), expected)};
}

// `coordinates` names the pair, "x, y" for map points, "x, z" for a bed profile.
std::vector<Point> points(const json& v, const std::string& path, std::size_t min_count,
                          const std::string& coordinates = "x, y") {
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

// Requires o[key] > o[lower_key] = lower; used for the x_min < x_max pairs of boxes.
void check_above(const Object& o, std::string_view key, double value, std::string_view lower_key,
                 double lower) {
  if (value > lower) return;
  throw ScenarioError(
      o.path(key), describe(*o.find(key)) + " with " + std::string(lower_key) + " = " + fmt(lower),
      "a number > " + std::string(lower_key) + " (metres)");
}

// The four box keys of `o`, all required, min < max on both axes.
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
const std::string kBoxExpected = "an object with x_min, x_max, y_min, y_max (metres)";

Rectangle read_box(const json& v, const std::string& path) {
  return box(Object(v, path, kBoxKeys, kBoxExpected));
}

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

// Consecutive points must differ; for a polygon the last one also precedes the first.
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
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
      const Point &a = poly[i], &b = poly[(i + 1) % n], &c = poly[j], &d = poly[(j + 1) % n];
      if (!segments_meet(a, b, c, d)) continue;
      throw ScenarioError(path,
                          "edge " + std::to_string(i) + " " + fmt(a) + "-" + fmt(b) + " and edge " +
                              std::to_string(j) + " " + fmt(c) + "-" + fmt(d) + " intersecting",
                          expected);
    }
  }
  // Guards against outlines so thin that rounding hid their degeneracy from the tests above.
  const Rectangle bb = bounding_box(poly);
  const double w = bb.x_max - bb.x_min, h = bb.y_max - bb.y_min;
  if (std::abs(signed_area(poly)) <= 1e-12 * (w * w + h * h)) {
    throw ScenarioError(path, "a polygon of zero area", expected);
  }
}

std::vector<Point> read_polygon(const json& v, const std::string& path) {
  std::vector<Point> poly = points(v, path, 3);
  check_distinct_neighbours(poly, path, true);
  check_simple(poly, path);
  return poly;
}

std::vector<Point> corners(const Rectangle& r) {
  return {{r.x_min, r.y_min}, {r.x_max, r.y_min}, {r.x_max, r.y_max}, {r.x_min, r.y_max}};
}

// Water must start inside the domain: particles outside it would be removed at once.
// `vertex_paths` points errors at the offending polygon vertex rather than at the whole shape.
void check_inside(const std::vector<Point>& poly, const Rectangle& domain, const std::string& path,
                  bool vertex_paths) {
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
    throw ScenarioError(vertex_paths ? element_path(path, i) : path,
                        "the point " + fmt(p) + " outside the domain [" + fmt(domain.x_min) + ", " +
                            fmt(domain.x_max) + "] x [" + fmt(domain.y_min) + ", " +
                            fmt(domain.y_max) + "]",
                        "water lying inside the domain");
  }
}

// ---------------------------------------------------------------------------------------------
// Sections of the scene

swe::Settings read_numerics(const json* v, double gravity) {
  const Object o(v ? *v : empty_object(), "/numerics",
                 {"cfl", "alpha_e", "gradient", "min_time_step"}, "an object");
  swe::Settings s;
  s.gravity_m_s2 = gravity;
  s.cfl = bounded(o, "cfl", 0.0, true, 1.0, "the Courant number", s.cfl);
  // Below 1 the support holds too few neighbours for a stable gradient; above 3 the smoothing
  // is so wide that the answer no longer resolves the flow. Either is surely a mistake.
  s.alpha_e = bounded(o, "alpha_e", 1.0, false, 3.0,
                      "support radius r_e = alpha_e sqrt(A_max), in particle sizes", s.alpha_e);
  const std::string_view gradient = choice(o, "gradient", {"mps", "summation"}, "mps");
  s.gradient =
      gradient == "summation" ? swe::GradientVariant::summation : swe::GradientVariant::mps;
  s.min_time_step_s = positive(o, "min_time_step", kSeconds, s.min_time_step_s);
  return s;
}

WaterBody read_water(const json& v, const std::string& path, const Rectangle& domain) {
  const Object o(v, path, {"depth", "velocity", "spacing", "rectangle", "polygon"},
                 "an object describing a body of water");
  const std::string one_shape = "exactly one of \"rectangle\" or \"polygon\"";
  const json* rectangle = o.find("rectangle");
  const json* polygon = o.find("polygon");
  if (rectangle && polygon) {
    throw ScenarioError(path, "both \"rectangle\" and \"polygon\"", one_shape);
  }
  if (!rectangle && !polygon) {
    throw ScenarioError(path, "neither \"rectangle\" nor \"polygon\"", one_shape);
  }

  WaterBody w;
  if (rectangle) {
    w.polygon = corners(read_box(*rectangle, o.path("rectangle")));
    check_inside(w.polygon, domain, o.path("rectangle"), false);
  } else {
    w.polygon = read_polygon(*polygon, o.path("polygon"));
    check_inside(w.polygon, domain, o.path("polygon"), true);
  }
  w.depth_m = positive(o, "depth", kMetres);
  if (const json* velocity = o.find("velocity")) {
    w.velocity_m_s = pair(*velocity, o.path("velocity"), "a [u, v] pair of numbers (m/s)");
  }

  // A spacing wider than the shape would fill it with at most one row of particles.
  w.spacing_m = positive(o, "spacing", kMetres);
  const Rectangle bb = bounding_box(w.polygon);
  const double width = bb.x_max - bb.x_min, height = bb.y_max - bb.y_min;
  const double limit = std::min(width, height);
  if (w.spacing_m > limit * (1.0 + 1e-12)) {
    throw ScenarioError(
        o.path("spacing"),
        describe(*o.find("spacing")) + " for water " + fmt(width) + " m x " + fmt(height) + " m",
        "a number > 0 and at most " + fmt(limit) +
            " (the smaller side of the water's bounding box, metres)");
  }
  return w;
}

std::vector<WaterBody> read_waters(const json* v, const Rectangle& domain) {
  const std::string path = "/water";
  const std::string expected = "a non-empty array of water bodies";
  if (v == nullptr) throw ScenarioError(path, kMissing, expected);
  if (!v->is_array() || v->empty()) throw ScenarioError(path, describe(*v), expected);
  std::vector<WaterBody> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    out.push_back(read_water((*v)[i], element_path(path, i), domain));
  }
  return out;
}

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

BedSpec read_bed(const json* v) {
  if (v == nullptr) return {};
  const std::string path = "/bed";
  const std::string one_kind = "exactly one of \"plane\" or \"profile_x\"";
  const Object o(*v, path, {"plane", "profile_x"}, "an object with " + one_kind);
  const json* plane = o.find("plane");
  const json* profile = o.find("profile_x");
  if ((plane != nullptr) == (profile != nullptr)) {
    throw ScenarioError(
        path, plane ? "both \"plane\" and \"profile_x\"" : "neither \"plane\" nor \"profile_x\"",
        one_kind);
  }
  if (plane) {
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
  spec.points = points(*profile, o.path("profile_x"), 2, "x, z");
  for (std::size_t i = 1; i < spec.points.size(); ++i) {
    if (!(spec.points[i][0] > spec.points[i - 1][0])) {
      throw ScenarioError(element_path(o.path("profile_x"), i), "x = " + fmt(spec.points[i][0]),
                          "x greater than the previous point's " + fmt(spec.points[i - 1][0]) +
                              " ([x, z] points with x strictly increasing)");
    }
  }
  return spec;
}

std::optional<double> read_friction(const json* v) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, "/friction", {"manning_n"}, "an object with \"manning_n\"");
  return positive(o, "manning_n", "s m^-1/3");
}

std::optional<splitting::SplittingSettings> read_splitting(const json* v) {
  if (v == nullptr) return std::nullopt;
  const Object o(*v, "/splitting", {"threshold", "alpha_s", "max_particles", "axis"},
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
  return s;
}

std::vector<double> listed_times(const json& v, const std::string& path, double end_time) {
  if (!v.is_array()) throw ScenarioError(path, describe(v), "an array of times (seconds)");
  const std::string expected = "a time in (0, end_time = " + fmt(end_time) + "] (seconds)";
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double t = finite_number(v[i], element_path(path, i), expected);
    if (!(t > 0.0) || t > end_time) {
      throw ScenarioError(element_path(path, i), describe(v[i]), expected);
    }
    out.push_back(t);
  }
  return out;
}

// interval, 2 interval, ... up to end_time; end_time itself is added by the caller. A multiple
// within rounding of end_time is dropped so the run does not write two records a hair apart.
std::vector<double> regular_times(const Object& o, double end_time) {
  const double interval = positive(o, "interval", kSeconds);
  if (end_time / interval > kMaxOutputTimes) {
    throw ScenarioError(
        o.path("interval"),
        describe(*o.find("interval")) + ", giving " + fmt(end_time / interval) + " output times",
        "an interval giving at most " + fmt(kMaxOutputTimes) + " output times (seconds)");
  }
  const double slack = 1e-9 * end_time;
  std::vector<double> out;
  for (std::size_t k = 1;; ++k) {
    const double t = static_cast<double>(k) * interval;
    if (t >= end_time - slack) break;
    out.push_back(t);
  }
  return out;
}

std::vector<double> read_times(const Object& o, double end_time) {
  const json* times = o.find("times");
  const json* interval = o.find("interval");
  if (times && interval) {
    throw ScenarioError(o.path(), "both \"times\" and \"interval\"",
                        "at most one of \"times\" or \"interval\"");
  }
  std::vector<double> out;
  if (times) {
    out = listed_times(*times, o.path("times"), end_time);
  } else if (interval) {
    out = regular_times(o, end_time);
  }
  out.push_back(end_time);  // the final state is always worth having
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double smallest_spacing(const std::vector<WaterBody>& water) {
  double s = water.front().spacing_m;
  for (const WaterBody& w : water) s = std::min(s, w.spacing_m);
  return s;
}

GridSpec read_grid(const json* v, const std::string& path, const Scenario& scene) {
  const Object o(v ? *v : empty_object(), path, {"spacing", "x_min", "x_max", "y_min", "y_max"},
                 "an object");
  GridSpec grid;
  // Half the particle spacing resolves the particle field without empty cells between them.
  grid.spacing_m = positive(o, "spacing", kMetres, 0.5 * smallest_spacing(scene.water));

  std::vector<std::string_view> present;
  for (std::string_view key : kBoxKeys) {
    if (o.find(key) != nullptr) present.push_back(key);
  }
  if (present.empty()) {
    grid.bounds = scene.domain;
  } else if (present.size() == kBoxKeys.size()) {
    grid.bounds = box(o);
  } else {
    throw ScenarioError(path, "only " + join(present, false),
                        "all four of x_min, x_max, y_min, y_max, or none (the domain)");
  }

  const double cells = ((grid.bounds.x_max - grid.bounds.x_min) / grid.spacing_m) *
                       ((grid.bounds.y_max - grid.bounds.y_min) / grid.spacing_m);
  if (cells > kMaxGridCells) {
    throw ScenarioError(o.path("spacing"),
                        fmt(grid.spacing_m) + ", giving about " + fmt(std::ceil(cells)) + " cells",
                        "a spacing giving at most " + fmt(kMaxGridCells) + " grid cells (metres)");
  }
  return grid;
}

std::filesystem::path read_output_path(const Object& o, const std::string& name,
                                       const std::filesystem::path& base_dir) {
  const std::string expected = "a file name or path (relative to the scenario's folder)";
  const std::string text = optional_string(o, "path", expected).value_or(name + ".nc");
  std::filesystem::path p(text);
  if (text.empty() || !p.has_filename()) {
    const std::string found = "a string " + literal(text);
    throw ScenarioError(o.path("path"), text.empty() ? found : found + ", which names a folder",
                        expected);
  }
  if (p.is_relative()) p = base_dir / p;
  return std::filesystem::absolute(p).lexically_normal();
}

Output read_output(const json* v, const Scenario& scene, const std::filesystem::path& base_dir) {
  const std::string path = "/output";
  const Object o(v ? *v : empty_object(), path, {"path", "times", "interval", "grid", "particles"},
                 "an object");
  Output out;
  out.path = read_output_path(o, scene.name, base_dir);
  out.times_s = read_times(o, scene.end_time_s);
  out.grid = read_grid(o.find("grid"), o.path("grid"), scene);
  out.write_particles = optional_bool(o, "particles", true);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Parsing the text

// Follows the parser through the document so that a key given twice in one object - which
// the JSON library would resolve silently by keeping the last - is reported with its path.
class DuplicateKeyGuard {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    using Event = json::parse_event_t;
    switch (event) {
      case Event::key: on_key(parsed.get<std::string>()); break;
      case Event::object_start:
      case Event::array_start: {
        std::string path = frames_.empty() ? std::string() : next_child();
        frames_.push_back(Frame{event == Event::array_start, std::move(path), {}, {}, 0});
        break;
      }
      case Event::object_end:
      case Event::array_end: frames_.pop_back(); break;
      case Event::value:
        if (!frames_.empty()) next_child();  // counts array elements
        break;
    }
    return true;  // keep everything
  }

 private:
  struct Frame {
    bool array;
    std::string path;
    std::set<std::string> keys;
    std::string current;  // path of the member being read, in an object
    std::size_t next_index;
  };

  void on_key(const std::string& key) {
    Frame& f = frames_.back();
    f.current = member_path(f.path, key);
    if (!f.keys.insert(key).second) {
      throw ScenarioError(f.current, "the key " + literal(key) + " a second time",
                          "each key at most once in an object");
    }
  }

  // The path of the value that starts now inside the innermost container.
  std::string next_child() {
    Frame& f = frames_.back();
    return f.array ? element_path(f.path, f.next_index++) : f.current;
  }

  std::vector<Frame> frames_;
};

// "line L, column C" of a byte offset, counted as the JSON library counts them.
std::string line_and_column(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(byte, text.size());
  std::size_t line = 1, column = 0;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 0;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The library's message without its "[json.exception.parse_error.N] parse error at ...: "
// prefix, which repeats what line_and_column already says.
std::string bare_parse_message(const std::string& what) {
  std::string msg = what;
  if (const auto bracket = msg.find("] ");
      !msg.empty() && msg[0] == '[' && bracket != std::string::npos) {
    msg.erase(0, bracket + 2);
  }
  if (msg.rfind("parse error", 0) == 0) {
    if (const auto colon = msg.find(": "); colon != std::string::npos) msg.erase(0, colon + 2);
  }
  return msg;
}

json parse_json(const std::string& text) {
  DuplicateKeyGuard guard;
  try {
    return json::parse(text, std::ref(guard));
  } catch (const json::parse_error& e) {
    throw ScenarioError(
        "",
        "invalid JSON at " + line_and_column(text, e.byte) + ": " + bare_parse_message(e.what()),
        "valid JSON");
  } catch (const json::exception& e) {
    // A number literal beyond double range ends up here, without a position.
    throw ScenarioError("", "invalid JSON: " + bare_parse_message(e.what()), "valid JSON");
  }
}

}  // namespace

Scenario parse(const std::string& text, const std::filesystem::path& base_dir,
               const std::string& default_name) {
  const json root = parse_json(text);
  const Object o(root, "",
                 {"name", "description", "gravity", "end_time", "numerics", "domain", "water",
                  "walls", "bed", "friction", "splitting", "output"},
                 "a JSON object describing the scene");
  Scenario s;
  s.name = optional_string(o, "name", "a non-empty string").value_or(default_name);
  if (s.name.empty()) {
    throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
  }
  s.description = optional_string(o, "description", "a string").value_or("");

  const double gravity = positive(o, "gravity", "m/s^2", swe::Settings{}.gravity_m_s2);
  s.end_time_s = positive(o, "end_time", kSeconds);
  s.numerics = read_numerics(o.find("numerics"), gravity);

  const json* domain = o.find("domain");
  if (domain == nullptr) throw ScenarioError(o.path("domain"), kMissing, kBoxExpected);
  s.domain = read_box(*domain, o.path("domain"));

  s.water = read_waters(o.find("water"), s.domain);
  s.walls = read_walls(o.find("walls"));
  s.bed = read_bed(o.find("bed"));
  s.manning_n = read_friction(o.find("friction"));
  s.splitting = read_splitting(o.find("splitting"));
  s.output = read_output(o.find("output"), s, base_dir);
  return s;
}

Scenario load(const std::filesystem::path& file) {
  const std::string expected = "a readable scenario JSON file";
  const std::string cannot = "cannot read file '" + file.string() + "': ";
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    throw ScenarioError("", cannot + "it is a folder", expected);
  }

  errno = 0;  // so that a failure without a system reason is not blamed on an old one
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw ScenarioError("", cannot + (err != 0 ? std::strerror(err) : "cannot open it"), expected);
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw ScenarioError("", cannot + "read failed", expected);

  const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
  const std::filesystem::path folder = absolute.parent_path();
  // A case kept as <case>/scenario.json is named after its folder; any other file after itself.
  const std::string name = absolute.filename() == "scenario.json" ? folder.filename().string()
                                                                  : absolute.stem().string();
  return parse(buffer.str(), folder, name.empty() ? "scenario" : name);
}

}  // namespace swemps::scenario
