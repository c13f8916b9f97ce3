// The "water" section of a scene file: bodies of water given by a uniform depth, a level
// filled over the terrain or a depth raster, each with its shape, velocity, spacing and volume
// rule. The rest of the scene is load.cpp's; the strict JSON reading is json_reading.hpp's.

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "json_reading.hpp"
#include "load_sections.hpp"
#include "swemps/particles/seeding.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// ---------------------------------------------------------------------------------------------
// Water

struct ParsedWater {
  WaterBody body;
  bool volumes_given = false;
};

// The shape in `o`: exactly one of "rectangle" or "polygon", or neither when `optional`.
// Checked against the domain when the domain is known.
std::optional<std::vector<Point>> read_shape(const Object& o, bool optional,
                                             const std::optional<Rectangle>& domain) {
  const std::string one_shape = "exactly one of \"rectangle\" or \"polygon\"";
  const json* rectangle = o.find("rectangle");
  const json* polygon = o.find("polygon");
  if (rectangle && polygon) {
    throw ScenarioError(o.path(), "both \"rectangle\" and \"polygon\"",
                        optional ? "at most one of \"rectangle\" or \"polygon\"" : one_shape);
  }
  if (!rectangle && !polygon) {
    if (optional) return std::nullopt;
    throw ScenarioError(o.path(), "neither \"rectangle\" nor \"polygon\"", one_shape);
  }
  std::vector<Point> poly;
  if (rectangle) {
    poly = corners(read_box(*rectangle, o.path("rectangle")));
    if (domain) check_inside(poly, *domain, o.path("rectangle"), false);
  } else {
    poly = read_polygon(*polygon, o.path("polygon"));
    if (domain) check_inside(poly, *domain, o.path("polygon"), true);
  }
  return poly;
}

// "solitary_wave": a wave over the body's still water (tsunami/solitary_wave.hpp). The still
// depth, when given, must exceed the height; the crest is checked against the domain with the
// shapes (check_within_domain).
SolitaryWaveStart read_solitary_wave(const json& v, const std::string& path) {
  const Object o(v, path, {"height", "depth", "crest", "direction"},
                 "an object with \"height\", \"crest\" and \"direction\", and optionally "
                 "\"depth\"");
  SolitaryWaveStart wave;
  wave.height_m = positive(o, "height", kMetres);
  if (o.find("depth") != nullptr) {
    const double depth = positive(o, "depth", kMetres);
    if (!(depth > wave.height_m)) {
      throw ScenarioError(o.path("depth"),
                          fmt(depth) + " m, not above the height " + fmt(wave.height_m) + " m",
                          "the still water's depth under the wave, greater than its height");
    }
    wave.still_depth_m = depth;
  }
  const json* crest = o.find("crest");
  if (crest == nullptr) {
    throw ScenarioError(o.path("crest"), kMissing, "an [x, y] point on the crest line (m)");
  }
  wave.crest_m = pair(*crest, o.path("crest"), "an [x, y] point on the crest line (m)");
  const json* direction = o.find("direction");
  if (direction == nullptr) {
    throw ScenarioError(o.path("direction"), kMissing,
                        "an [x, y] vector, the way the wave travels");
  }
  wave.direction =
      pair(*direction, o.path("direction"), "an [x, y] vector, the way the wave travels");
  if (wave.direction[0] == 0.0 && wave.direction[1] == 0.0) {
    throw ScenarioError(o.path("direction"), "[0, 0]",
                        "a non-zero [x, y] vector, the way the wave travels");
  }
  return wave;
}

// "velocity": a [u, v] pair, or an object naming two rasters, {"u": ..., "v": ...}.
void read_velocity(const Object& o, const std::filesystem::path& base_dir, WaterBody& w) {
  const json* velocity = o.find("velocity");
  if (velocity == nullptr) return;
  if (!velocity->is_object()) {
    w.velocity_m_s = pair(*velocity, o.path("velocity"),
                          "a [u, v] pair of numbers (m/s), or an object {\"u\": raster, "
                          "\"v\": raster}");
    return;
  }
  const Object rasters(*velocity, o.path("velocity"), {"u", "v"},
                       "an object with \"u\" and \"v\", rasters of the velocity's east and "
                       "north components (m/s)");
  w.velocity_rasters = VelocityRasters{
      RasterSpec{file_path(rasters, "u", "a raster of the east velocity (m/s)", base_dir), {}},
      RasterSpec{file_path(rasters, "v", "a raster of the north velocity (m/s)", base_dir), {}}};
}

// A key that does not belong to the way this body of water is given.
void forbid(const Object& o, std::string_view key, std::string_view form,
            const std::string& belongs) {
  if (o.find(key) == nullptr) return;
  throw ScenarioError(o.path(key),
                      "the key " + literal(key) + " in water given by " + literal(form),
                      "no " + literal(key) + " here (" + belongs + ")");
}

ParsedWater read_water(const json& v, const std::string& path,
                       const std::optional<Rectangle>& domain, bool has_bed,
                       const std::filesystem::path& base_dir, double default_spacing_m,
                       swe::SchemeKind scheme) {
  const Object o(
      v, path,
      {"name", "depth", "fill", "surface_elevation", "depth_raster", "crs", "min_depth", "velocity",
       "surface_displacement", "solitary_wave", "spacing", "volumes", "rectangle", "polygon"},
      "an object describing a body of water");
  std::vector<std::string_view> forms;
  for (std::string_view key : {"depth", "fill", "depth_raster"}) {
    if (o.find(key) != nullptr) forms.push_back(key);
  }
  if (forms.size() > 1) {
    throw ScenarioError(path, several(forms),
                        "exactly one of \"depth\", \"fill\" or \"depth_raster\" (how deep the "
                        "water is)");
  }
  // Without any of the three the body is taken as the original form, whose depth is missing.
  const std::string_view form = forms.empty() ? "depth" : forms.front();

  ParsedWater parsed;
  WaterBody& w = parsed.body;
  // The body's provenance label (docs/provenance.md); bodies that share a name share one.
  w.name = optional_string(o, "name", "a non-empty string").value_or(WaterBody::kDefaultName);
  if (w.name.empty()) {
    throw ScenarioError(o.path("name"), describe(*o.find("name")), "a non-empty string");
  }
  const std::string with_fill = "it goes with \"fill\"";
  const std::string with_raster = "it goes with \"depth_raster\"";
  if (form == "depth") {
    w.polygon = *read_shape(o, false, domain);
    w.depth = UniformDepth{positive(o, "depth", kMetres)};
    forbid(o, "surface_elevation", form, with_fill);
    forbid(o, "min_depth", form, "it goes with \"fill\" or \"depth_raster\"");
    forbid(o, "crs", form, with_raster);
  } else if (form == "fill") {
    const std::string inside = "with \"fill\" the shape goes inside it";
    forbid(o, "rectangle", form, inside);
    forbid(o, "polygon", form, inside);
    forbid(o, "crs", form, with_raster);
    if (!has_bed) {
      throw ScenarioError(o.path("fill"), "\"fill\" in a scene without a \"bed\"",
                          "a \"bed\" to fill (the depth is surface_elevation minus the bed "
                          "elevation)");
    }
    const Object shape(*o.find("fill"), o.path("fill"), {"rectangle", "polygon", "from"},
                       "an object with exactly one of \"rectangle\" or \"polygon\", and "
                       "optionally \"from\"");
    w.polygon = *read_shape(shape, false, domain);
    LevelSurface level{
        number(o, "surface_elevation", "a number (metres, the level of the water surface)"),
        std::nullopt};
    if (const json* from = shape.find("from")) {
      const auto point = pair(*from, shape.path("from"), "an [x, y] pair of numbers (m)");
      if (!particles::point_in_polygon(w.polygon, point)) {
        throw ScenarioError(shape.path("from"),
                            "the point (" + fmt(point[0]) + ", " + fmt(point[1]) +
                                ") outside the fill's shape",
                            "a point inside the shape, in the water the lake grows from");
      }
      level.from = point;
    }
    w.depth = level;
  } else {
    forbid(o, "surface_elevation", form, with_fill);
    w.polygon = read_shape(o, true, domain).value_or(std::vector<Point>{});
    w.depth = DepthRaster{RasterSpec{
        file_path(o, "depth_raster", "a raster of water depths (metres)", base_dir), crs_text(o)}};
  }
  if (form != "depth") w.min_depth_m = non_negative(o, "min_depth", kMetres, w.min_depth_m);
  read_velocity(o, base_dir, w);
  const json* displacement = o.find("surface_displacement");
  const json* wave = o.find("solitary_wave");
  if (displacement && wave) {
    throw ScenarioError(path, "both \"surface_displacement\" and \"solitary_wave\"",
                        "at most one of them (how the surface starts displaced)");
  }
  if ((displacement || wave) && form == "depth_raster") {
    const std::string_view key = displacement ? "surface_displacement" : "solitary_wave";
    forbid(o, key, form,
           "it goes with \"depth\" or \"fill\"; a depth raster gives the displaced depth "
           "itself");
  }
  if (wave) w.displacement = read_solitary_wave(*wave, o.path("solitary_wave"));
  if (displacement) {
    w.displacement = DisplacementRaster{RasterSpec{
        file_path(o, "surface_displacement", "a raster of the surface's rise (metres)", base_dir),
        {}}};
  }

  // A spacing wider than the shape would fill it with at most one row of particles. The
  // default of model ns is the tank's lattice, which reports water it cannot fill itself.
  const bool spacing_given = o.find("spacing") != nullptr || !(default_spacing_m > 0.0);
  w.spacing_m = spacing_given ? positive(o, "spacing", kMetres) : default_spacing_m;
  if (spacing_given && !w.polygon.empty()) {
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
  }

  // Under the seed scheme water whose depth comes from the terrain starts at rest only when
  // balanced, as eq 7 sums some 15 % too deep. The conservative scheme sums lattice water to
  // its true depth, and balancing has no fixed point there (a particle's own volume sets its
  // radius, not its depth): its water keeps the volume the terrain gives it.
  const bool seed = scheme == swe::SchemeKind::seed;
  const std::string_view volumes = choice(o, "volumes", {"geometric", "balanced"},
                                          form == "depth" || !seed ? "geometric" : "balanced");
  w.volumes = volumes == "balanced" ? VolumeRule::balanced : VolumeRule::geometric;
  if (w.volumes == VolumeRule::balanced && !seed) {
    throw ScenarioError(o.path("volumes"), "\"balanced\" under the conservative scheme",
                        "\"geometric\" or no \"volumes\" (balancing corrects the seed scheme's "
                        "eq 7 depth; the conservative scheme sums lattice water to its true "
                        "depth; see \"scheme\")");
  }
  parsed.volumes_given = o.find("volumes") != nullptr;
  return parsed;
}

// Missing or empty water is allowed here; parse() requires water or an inflow.
// `default_spacing_m`: the particle spacing of water that gives none (model ns, whose lattice
// spacing is the "ns" block's); 0: each body must give one.
}  // namespace

std::vector<WaterBody> read_waters(const json* v, const std::optional<Rectangle>& domain,
                                   bool has_bed, const std::filesystem::path& base_dir,
                                   double default_spacing_m, swe::SchemeKind scheme) {
  const std::string path = "/water";
  if (v == nullptr) return {};
  if (!v->is_array()) throw ScenarioError(path, describe(*v), "an array of water bodies");
  std::vector<ParsedWater> parsed;
  for (std::size_t i = 0; i < v->size(); ++i) {
    parsed.push_back(
        read_water((*v)[i], element_path(path, i), domain, has_bed, base_dir, default_spacing_m,
                   scheme));
  }
  // Balancing solves for all particles at once (their depths are sums over neighbours, across
  // bodies too), so it is one choice for the whole scene.
  const auto balanced = std::find_if(parsed.begin(), parsed.end(), [](const ParsedWater& p) {
    return p.body.volumes == VolumeRule::balanced;
  });
  std::vector<WaterBody> out;
  for (std::size_t i = 0; i < parsed.size(); ++i) {
    WaterBody& body = parsed[i].body;
    if (balanced != parsed.end() && body.volumes == VolumeRule::geometric) {
      if (parsed[i].volumes_given) {
        const auto other = static_cast<std::size_t>(balanced - parsed.begin());
        throw ScenarioError(
            member_path(element_path(path, i), "volumes"),
            "\"geometric\" while " + element_path(path, other) + " is balanced",
            "\"balanced\" or no \"volumes\" (balancing solves for all particles together, so "
            "one balanced body balances them all)");
      }
      body.volumes = VolumeRule::balanced;
    }
    out.push_back(std::move(body));
  }
  return out;
}

}  // namespace swemps::scenario
