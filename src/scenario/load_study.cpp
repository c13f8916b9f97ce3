// Study files: JSON text -> study::Study, with the strict reading of scenario files
// (json_reading.hpp): unknown keys, wrong types and values out of range are errors naming
// their JSON path.

#include <cmath>
#include <functional>

#include "json_reading.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/study_file.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// o[key], a path the study names, relative to the study file's folder.
std::filesystem::path file_path(const Object& o, std::string_view key, const std::string& what,
                                const std::filesystem::path& base_dir) {
  return path_value(o, key, what, base_dir, "the study file's folder");
}

study::RitterReference read_ritter(const json& v, const std::string& path) {
  const Object o(v, path, {"dam_x", "depth", "reservoir_start_x"},
                 "an object with dam_x and depth (metres)");
  study::RitterReference r;
  r.dam_x_m = number(o, "dam_x", "a number (metres): the dam's x");
  r.initial_depth_m = positive(o, "depth", "metres: the reservoir's depth h0");
  r.reservoir_start_x_m = number(o, "reservoir_start_x", "a number (metres) < dam_x", 0.0);
  if (!(r.reservoir_start_x_m < r.dam_x_m)) {
    throw ScenarioError(o.path("reservoir_start_x"),
                        fmt(r.reservoir_start_x_m) + " with dam_x = " + fmt(r.dam_x_m),
                        "a number (metres) < dam_x: the reservoir's back wall");
  }
  return r;
}

// A raster the study names: a file, or a GDAL dataset name wrapping one
// (NETCDF:"run.nc":max_depth), its file taken relative to the study file's folder.
std::string raster_name(const Object& o, std::string_view key, const std::string& what,
                        const std::filesystem::path& base_dir) {
  const json* v = o.find(key);
  const std::string expected =
      "a path to " + what + " (relative to the study file's folder), or a GDAL dataset name";
  if (v == nullptr) throw ScenarioError(o.path(key), kMissing, expected);
  if (!v->is_string() || v->get_ref<const std::string&>().empty()) {
    throw ScenarioError(o.path(key), describe(*v), expected);
  }
  const std::string text = v->get<std::string>();
  const auto resolve = [&](const std::string& name) {
    std::filesystem::path p(name);
    if (p.is_relative()) p = base_dir / p;
    return std::filesystem::absolute(p).lexically_normal().string();
  };
  if (const auto wrapped = io::split_dataset_name(text)) {
    return wrapped->driver + ":\"" + resolve(wrapped->file) + "\"" + wrapped->rest;
  }
  return resolve(text);
}

// {"table": "gauges.csv", "columns": {"<gauge>": "<column>", ...}}
void read_gauge_reference(const json& v, const std::string& path,
                          const std::filesystem::path& base_dir, study::MapReference& r) {
  const std::string expected =
      "an object {\"table\": CSV file, \"columns\": {gauge name: column name, ...}}";
  const Object o(v, path, {"table", "columns"}, expected);
  r.gauge_table = file_path(o, "table", "a CSV table of depths at the gauges", base_dir);
  const json* columns = o.find("columns");
  if (columns == nullptr) throw ScenarioError(o.path("columns"), kMissing, expected);
  const std::string columns_expected =
      "a non-empty object naming, for each gauge compared, the table's column of its depth";
  if (!columns->is_object() || columns->empty()) {
    throw ScenarioError(o.path("columns"), describe(*columns), columns_expected);
  }
  for (auto it = columns->begin(); it != columns->end(); ++it) {
    const std::string at = member_path(o.path("columns"), it.key());
    if (!it->is_string() || it->get_ref<const std::string&>().empty()) {
      throw ScenarioError(at, describe(*it), "the name of a column of the table");
    }
    r.gauge_columns.push_back({it.key(), it->get<std::string>()});
  }
}

study::Reference read_reference(const Object& root, const std::filesystem::path& base_dir) {
  const std::string expected =
      "an object naming the reference: {\"ritter\": {...}}, {\"max_depth\": raster, ...} or "
      "{\"finest_run\": {}}";
  const json* v = root.find("reference");
  if (v == nullptr) throw ScenarioError(root.path("reference"), kMissing, expected);
  const Object o(*v, root.path("reference"), {"ritter", "max_depth", "gauges", "finest_run"},
                 expected);
  const int kinds = (o.find("ritter") != nullptr) + (o.find("max_depth") != nullptr) +
                    (o.find("finest_run") != nullptr);
  if (kinds != 1) {
    throw ScenarioError(root.path("reference"),
                        kinds == 0 ? "no reference" : "more than one kind of reference", expected);
  }
  if (o.find("gauges") != nullptr && o.find("max_depth") == nullptr) {
    throw ScenarioError(o.path("gauges"), "gauges without a map",
                        "gauge series only beside \"max_depth\"");
  }
  if (const json* ritter = o.find("ritter")) return read_ritter(*ritter, o.path("ritter"));
  if (const json* finest = o.find("finest_run")) {
    Object(*finest, o.path("finest_run"), {}, "{} (the finest run is the reference)");
    return study::FinestRunReference{};
  }
  study::MapReference map;
  map.max_depth = raster_name(o, "max_depth", "a raster of the maximum depth (metres)", base_dir);
  if (const json* gauges = o.find("gauges")) {
    read_gauge_reference(*gauges, o.path("gauges"), base_dir, map);
  }
  return map;
}

// o[key], an optional non-empty array of values, each read by `read(value, path)`. A value
// given twice is an error: it would only run the same thing twice.
template <class Value>
std::vector<Value> read_axis(const Object& o, std::string_view key, const std::string& what,
                             const std::function<Value(const json&, const std::string&)>& read) {
  const json* v = o.find(key);
  if (v == nullptr) return {};
  const std::string path = o.path(key);
  if (!v->is_array() || v->empty()) {
    throw ScenarioError(path, describe(*v), "a non-empty array of " + what);
  }
  std::vector<Value> values;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const json& element = (*v)[i];
    values.push_back(read(element, element_path(path, i)));
    for (std::size_t j = 0; j < i; ++j) {
      if ((*v)[j] != element) continue;
      throw ScenarioError(element_path(path, i),
                          describe(element) + " again (same as element " + std::to_string(j) + ")",
                          "each value once");
    }
  }
  return values;
}

// A number in (low, high] (or [low, high] when closed_low).
std::function<double(const json&, const std::string&)> number_in(double low, bool closed_low,
                                                                 double high,
                                                                 const std::string& meaning) {
  return [=](const json& v, const std::string& path) {
    const std::string expected = "a number in " + std::string(closed_low ? "[" : "(") + fmt(low) +
                                 ", " + fmt(high) + "] (" + meaning + ")";
    const double x = finite_number(v, path, expected);
    if (!(closed_low ? x >= low : x > low) || !(x <= high)) {
      throw ScenarioError(path, describe(v), expected);
    }
    return x;
  };
}

study::SplittingChoice read_splitting_choice(const json& v, const std::string& path) {
  // The scene file's bounds on the threshold (docs/scenario.md, splitting).
  const auto threshold = number_in(1.0, false, 4.0, "the area ratio A/A_0 that triggers a split");
  if (v.is_null()) return {};
  if (!v.is_number()) {
    throw ScenarioError(path, describe(v), "null (no splitting) or a threshold in (1, 4]");
  }
  return {threshold(v, path)};
}

swe::SchemeKind read_scheme(const json& v, const std::string& path) {
  return word(v, path, {"seed", "conservative"}) == "seed" ? swe::SchemeKind::seed
                                                           : swe::SchemeKind::conservative;
}

swe::GradientVariant read_gradient(const json& v, const std::string& path) {
  return word(v, path, {"mps", "summation"}) == "summation" ? swe::GradientVariant::summation
                                                            : swe::GradientVariant::mps;
}

study::Sweep read_sweep(const Object& root) {
  const json* v = root.find("sweep");
  const std::string expected =
      "an object of knob value lists (spacing, splitting, scheme, gradient, kappa, "
      "dissipation, shifting, cfl, alpha_e)";
  if (v == nullptr) throw ScenarioError(root.path("sweep"), kMissing, expected);
  const Object o(*v, root.path("sweep"),
                 {"spacing", "splitting", "scheme", "gradient", "kappa", "dissipation", "shifting",
                  "cfl", "alpha_e"},
                 expected);
  study::Sweep s;
  // Spacings beyond a kilometre are surely a typo for metres.
  s.spacing_m = read_axis<double>(o, "spacing", "particle spacings (metres)",
                                  number_in(0.0, false, 1e3, "the particle spacing in metres"));
  s.splitting = read_axis<study::SplittingChoice>(
      o, "splitting", "null (no splitting) or area-ratio thresholds", read_splitting_choice);
  s.scheme = read_axis<swe::SchemeKind>(o, "scheme", "\"seed\" or \"conservative\"", read_scheme);
  s.gradient =
      read_axis<swe::GradientVariant>(o, "gradient", "\"mps\" or \"summation\"", read_gradient);
  // The scene file's bounds (docs/scenario.md, numerics).
  s.kappa = read_axis<double>(o, "kappa", "kernel radii in particle sizes",
                              number_in(1.0, true, 2.5, "h = kappa sqrt(A)"));
  s.dissipation = read_axis<double>(o, "dissipation", "dissipation coefficients",
                                    number_in(0.0, true, 2.0, "the pairwise dissipation alpha"));
  s.shifting = read_axis<double>(o, "shifting", "particle shifting coefficients",
                                 number_in(0.0, true, 10.0, "the particle shifting beta"));
  // Unlike a scene, a study may push the Courant number past 1: finding where runs break
  // down is one thing a study is for.
  s.cfl = read_axis<double>(o, "cfl", "Courant numbers",
                            number_in(0.0, false, 100.0, "the Courant number"));
  s.alpha_e = read_axis<double>(o, "alpha_e", "support radii in particle sizes",
                                number_in(1.0, true, 3.0, "r_e = alpha_e sqrt(A_max)"));
  return s;
}

std::optional<int> read_jobs(const Object& o) {
  if (o.find("jobs") == nullptr) return std::nullopt;
  const std::string expected = "a whole number from 1 to 1024 (runs at once)";
  const double jobs = number(o, "jobs", expected);
  if (jobs < 1.0 || jobs > 1024.0 || jobs != std::floor(jobs)) {
    throw ScenarioError(o.path("jobs"), describe(*o.find("jobs")), expected);
  }
  return static_cast<int>(jobs);
}

study::Study read_study(const json& root_value, const std::filesystem::path& base_dir,
                        const std::filesystem::path& default_output) {
  const Object o(root_value, "",
                 {"description", "scene", "reference", "sweep", "profile_spacing_ratio",
                  "wet_depth", "jobs", "run_time_limit", "output"},
                 "a JSON object describing the study");
  optional_string(o, "description", "a string");  // free text, checked only for its type
  study::Study s;
  s.scene = file_path(o, "scene", "the scenario file every run starts from", base_dir);
  s.reference = read_reference(o, base_dir);
  s.sweep = read_sweep(o);
  const bool analytic = std::holds_alternative<study::RitterReference>(s.reference);
  // Each key belongs to one kind of reference; given to the other it would silently do nothing.
  if (!analytic && o.find("profile_spacing_ratio") != nullptr) {
    throw ScenarioError(o.path("profile_spacing_ratio"), describe(*o.find("profile_spacing_ratio")),
                        "no profile: maps are compared on the scene's output cells");
  }
  if (analytic && o.find("wet_depth") != nullptr) {
    throw ScenarioError(o.path("wet_depth"), describe(*o.find("wet_depth")),
                        "no wet depth: an analytic reference is compared on a depth profile");
  }
  // Below 1 the profile would be coarser than the particles and hide their error.
  s.profile_spacing_ratio = bounded(o, "profile_spacing_ratio", 1.0, false, 64.0,
                                    "profile cells per particle spacing", s.profile_spacing_ratio);
  if (o.find("wet_depth") != nullptr) {
    s.wet_depth_m =
        bounded(o, "wet_depth", 0.0, true, 100.0, "metres: a cell is wet when deeper", 0.0);
  }
  s.jobs = read_jobs(o);
  if (o.find("run_time_limit") != nullptr) {
    s.run_time_limit_s = bounded(o, "run_time_limit", 0.0, true, 1e7,
                                 "the wall-clock seconds one run may take", 0.0);
  }
  s.output = o.find("output") == nullptr
                 ? default_output
                 : file_path(o, "output", "the CSV table to write", base_dir);
  return s;
}

}  // namespace

study::Study parse_study(const std::string& text, const std::filesystem::path& base_dir,
                         const std::filesystem::path& default_output) {
  // The shared readers speak of scenarios; a study's messages say whose file is wrong.
  try {
    return read_study(parse_json(text), base_dir, default_output);
  } catch (const ScenarioError& e) {
    throw ScenarioError(e.json_path(), e.found(), e.expected(), "study");
  }
}

study::Study load_study(const std::filesystem::path& file) {
  const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
  const std::filesystem::path folder = absolute.parent_path();
  std::string text;
  try {
    text = read_text_file(file, "a readable study JSON file");
  } catch (const ScenarioError& e) {
    throw ScenarioError(e.json_path(), e.found(), e.expected(), "study");
  }
  std::filesystem::path default_output = folder / absolute.stem();
  default_output += ".csv";
  return parse_study(text, folder, default_output);
}

}  // namespace swemps::scenario
