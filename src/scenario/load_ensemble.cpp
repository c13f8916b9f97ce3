// Ensemble files: JSON text -> ensemble::Ensemble, with the strict reading of scenario files
// (json_reading.hpp); and the scene of each member, made from the base scene by JSON pointer.

#include <cmath>
#include <set>

#include "json_reading.hpp"
#include "swemps/io/raster_reader.hpp"
#include "swemps/scenario/ensemble_file.hpp"

namespace swemps::scenario {

using namespace json_reading;

namespace {

// A path the ensemble names, relative to the ensemble file's folder.
std::filesystem::path path_of(const Object& o, std::string_view key, const std::string& what,
                              const std::filesystem::path& base_dir) {
  return path_value(o, key, what, base_dir, "the ensemble file's folder");
}

// A whole number in [low, high] under `key`; nullopt when the key is absent.
std::optional<long long> whole(const Object& o, std::string_view key, long long low, long long high,
                               const std::string& meaning) {
  const json* v = o.find(key);
  if (v == nullptr) return std::nullopt;
  const std::string expected = "a whole number from " + std::to_string(low) + " to " +
                               std::to_string(high) + " (" + meaning + ")";
  if (!v->is_number_integer() &&
      !(v->is_number() && v->get<double>() == std::floor(v->get<double>()))) {
    throw ScenarioError(o.path(key), describe(*v), expected);
  }
  const double x = v->get<double>();
  if (!(x >= static_cast<double>(low) && x <= static_cast<double>(high))) {
    throw ScenarioError(o.path(key), describe(*v), expected);
  }
  return v->is_number_unsigned() ? static_cast<long long>(v->get<unsigned long long>())
                                 : static_cast<long long>(x);
}

// Whether the scene holds what `p` names. The library's own test throws, rather than answering
// no, for a part under an array that is empty ("/inflow/") or too large for an index.
bool scene_holds(const json& scene, const json::json_pointer& p) {
  try {
    return scene.contains(p);
  } catch (const json::exception&) {
    return false;
  }
}

// The value a pointer names goes into the base scene: an array's element must be there to be
// replaced; an object's key may be new, and so may objects above it ("/friction/manning_n" in
// a scene without friction). A misspelt key is still caught: each member's scene is read as
// strictly as any scene before anything runs.
void check_pointer(const json& scene, const std::string& pointer, const std::string& path) {
  const std::string expected =
      "a JSON pointer into the base scene (\"/friction/manning_n\", "
      "\"/inflow/0/hydrograph/1/1\")";
  json::json_pointer p;
  try {
    p = json::json_pointer(pointer);
  } catch (const json::exception&) {
    throw ScenarioError(path, literal(pointer) + ", not a JSON pointer", expected);
  }
  if (p.empty()) throw ScenarioError(path, "the whole scene (\"\")", expected);
  if (pointer == "/output/path") {
    throw ScenarioError(path, literal(pointer),
                        "a pointer to anything but the output path, which each member's run "
                        "writes into its own folder");
  }
  // The deepest part of the pointer that is in the scene, and what holds the first part
  // that is not.
  json::json_pointer there = p;
  while (!there.empty() && !scene_holds(scene, there)) there = there.parent_pointer();
  if (there == p) return;
  const json& holder = scene.at(there);
  if (holder.is_object()) return;
  throw ScenarioError(
      path, literal(pointer) + ", below " + describe(holder) + " at " + literal(there.to_string()),
      holder.is_array() && !holder.empty()
          ? "an index of an element that is there (0 to " + std::to_string(holder.size() - 1) +
                "): an ensemble replaces array elements, it does not add them"
          : expected + " that goes through objects and existing array elements");
}

ensemble::Knob read_knob(const json& v, const std::string& path, const json& scene) {
  const Object o(v, path, {"pointer", "name", "values", "range", "distribution"},
                 "an object with a \"pointer\" into the scene and either \"values\" or "
                 "\"range\"");
  ensemble::Knob k;
  const json* pointer = o.find("pointer");
  if (pointer == nullptr || !pointer->is_string()) {
    throw ScenarioError(o.path("pointer"), pointer ? describe(*pointer) : kMissing,
                        "a JSON pointer into the base scene, as a string");
  }
  k.pointer = pointer->get<std::string>();
  check_pointer(scene, k.pointer, o.path("pointer"));
  k.name = optional_string(o, "name", "a column name for the members table").value_or(k.pointer);
  if (k.name.empty()) throw ScenarioError(o.path("name"), "an empty string", "a column name");

  const json* values = o.find("values");
  const json* range = o.find("range");
  if ((values == nullptr) == (range == nullptr)) {
    throw ScenarioError(
        path, values ? "both \"values\" and \"range\"" : "neither \"values\" nor \"range\"",
        "either \"values\" (a list) or \"range\" ([low, high], sampled)");
  }
  if (values != nullptr) {
    if (!values->is_array() || values->empty()) {
      throw ScenarioError(o.path("values"), describe(*values), "a non-empty array of values");
    }
    for (std::size_t i = 0; i < values->size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if ((*values)[j] != (*values)[i]) continue;
        throw ScenarioError(
            element_path(o.path("values"), i),
            describe((*values)[i]) + " again (same as element " + std::to_string(j) + ")",
            "each value once");
      }
      k.values.push_back((*values)[i].dump());
    }
    if (o.find("distribution") != nullptr) {
      throw ScenarioError(o.path("distribution"), "a distribution for listed values",
                          "a distribution only with \"range\"");
    }
    return k;
  }
  const std::string expected = "[low, high]: two finite numbers, low < high";
  if (!range->is_array() || range->size() != 2) {
    throw ScenarioError(o.path("range"), describe(*range), expected);
  }
  k.low = finite_number((*range)[0], element_path(o.path("range"), 0), expected);
  k.high = finite_number((*range)[1], element_path(o.path("range"), 1), expected);
  if (!(k.low < k.high)) throw ScenarioError(o.path("range"), describe(*range), expected);
  k.distribution = choice(o, "distribution", {"uniform", "log_uniform"}, "uniform") == "log_uniform"
                       ? ensemble::Distribution::log_uniform
                       : ensemble::Distribution::uniform;
  if (k.distribution == ensemble::Distribution::log_uniform && !(k.low > 0.0)) {
    throw ScenarioError(o.path("range"), describe(*range),
                        "a range of positive numbers for a log_uniform distribution");
  }
  return k;
}

std::vector<ensemble::Knob> read_knobs(const Object& root, const json& scene) {
  const std::string expected = "a non-empty array of knobs: {\"pointer\": ..., \"values\": [...]}";
  const json* v = root.find("vary");
  if (v == nullptr) throw ScenarioError(root.path("vary"), kMissing, expected);
  if (!v->is_array() || v->empty()) throw ScenarioError(root.path("vary"), describe(*v), expected);
  std::vector<ensemble::Knob> knobs;
  std::set<std::string> pointers, names;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string path = element_path(root.path("vary"), i);
    knobs.push_back(read_knob((*v)[i], path, scene));
    if (!pointers.insert(knobs.back().pointer).second) {
      throw ScenarioError(member_path(path, "pointer"), literal(knobs.back().pointer) + " again",
                          "each pointer once");
    }
    if (!names.insert(knobs.back().name).second) {
      throw ScenarioError(path, "the name " + literal(knobs.back().name) + " again",
                          "a name (the members table's column) of its own");
    }
  }
  return knobs;
}

std::vector<double> read_thresholds(const Object& o, std::vector<double> fallback) {
  const json* v = o.find("thresholds");
  if (v == nullptr) return fallback;
  const std::string expected =
      "a non-empty array of depths in metres, each > 0, ascending (the depths whose "
      "exceedance the products map)";
  if (!v->is_array() || v->empty() || v->size() > 64) {
    throw ScenarioError(o.path("thresholds"), describe(*v), expected);
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string path = element_path(o.path("thresholds"), i);
    const double d = finite_number((*v)[i], path, expected);
    if (!(d > 0.0) || d > 1e4 || (!out.empty() && !(d > out.back()))) {
      throw ScenarioError(path, describe((*v)[i]), expected);
    }
    out.push_back(d);
  }
  return out;
}

ensemble::SlurmSettings read_slurm(const Object& root) {
  ensemble::SlurmSettings s;
  const json* v = root.find("slurm");
  if (v == nullptr) return s;
  const Object o(*v, root.path("slurm"),
                 {"partition", "account", "qos", "time", "memory", "max_running", "options"},
                 "an object of sbatch settings");
  const auto text = [&](std::string_view key, const std::string& what) {
    const std::string value = optional_string(o, key, what).value_or("");
    if (value.find_first_of(" \t\n\r'\"\\$`") != std::string::npos) {
      throw ScenarioError(o.path(key), literal(value), what + ", without blanks or quotes");
    }
    return value;
  };
  s.partition = text("partition", "a Slurm partition name");
  s.account = text("account", "a Slurm account name");
  s.qos = text("qos", "a Slurm quality of service");
  s.time_limit = text("time", "a time limit per member, as sbatch takes it (\"2:00:00\")");
  s.memory = text("memory", "memory per member, as sbatch takes it (\"4G\")");
  if (const auto n = whole(o, "max_running", 1, 100000, "members running at once")) {
    s.max_running = static_cast<int>(*n);
  }
  if (const json* extra = o.find("options")) {
    const std::string expected = "an array of sbatch options, each a string starting with '-'";
    if (!extra->is_array()) throw ScenarioError(o.path("options"), describe(*extra), expected);
    for (std::size_t i = 0; i < extra->size(); ++i) {
      const json& e = (*extra)[i];
      if (!e.is_string() || e.get_ref<const std::string&>().empty() ||
          e.get_ref<const std::string&>()[0] != '-' ||
          e.get_ref<const std::string&>().find_first_of("\n\r") != std::string::npos) {
        throw ScenarioError(element_path(o.path("options"), i), describe(e), expected);
      }
      s.extra.push_back(e.get<std::string>());
    }
  }
  return s;
}

ensemble::Ensemble read_ensemble(const json& root, const std::filesystem::path& file) {
  const Object o(
      root, "",
      {"description", "scene", "vary", "samples", "seed", "sampling", "thresholds",
       "threads_per_member", "jobs", "run_time_limit", "checkpoint_every", "folder", "slurm"},
      "a JSON object describing the ensemble");
  optional_string(o, "description", "a string");  // free text, checked only for its type
  const std::filesystem::path base_dir = file.parent_path();
  ensemble::Ensemble e;
  e.file = file;
  e.base_scene = path_of(o, "scene", "the scenario file every member starts from", base_dir);
  json scene;
  try {
    e.base_scene_text = read_text_file(e.base_scene, "a readable scenario JSON file");
    scene = parse_json(e.base_scene_text);
  } catch (const ScenarioError& error) {
    throw ScenarioError(o.path("scene"),
                        "a scene that cannot be read: " + std::string(error.what()),
                        "a readable scenario JSON file");
  }
  e.knobs = read_knobs(o, scene);
  const bool any_sampled =
      std::any_of(e.knobs.begin(), e.knobs.end(), [](const auto& k) { return k.sampled(); });
  const auto samples = whole(o, "samples", 1, 100000, "draws of the sampled knobs");
  const auto seed = whole(o, "seed", 0, 9007199254740991LL, "the sampling's seed");
  if (any_sampled && (!samples || !seed)) {
    throw ScenarioError(o.path(!samples ? "samples" : "seed"), kMissing,
                        "with a sampled knob (\"range\"), the number of draws \"samples\" and a "
                        "\"seed\", so that the members are the same on every machine");
  }
  if (!any_sampled && (samples || seed || o.find("sampling") != nullptr)) {
    throw ScenarioError(o.path(samples ? "samples"
                               : seed  ? "seed"
                                       : "sampling"),
                        "sampling settings without a sampled knob",
                        "\"samples\", \"seed\" and \"sampling\" only with a knob that has a "
                        "\"range\"");
  }
  if (any_sampled) {
    e.samples = static_cast<std::size_t>(*samples);
    e.seed = static_cast<std::uint64_t>(*seed);
    e.sampling = choice(o, "sampling", {"latin_hypercube", "random"}, "latin_hypercube") == "random"
                     ? ensemble::Sampling::random
                     : ensemble::Sampling::latin_hypercube;
  }
  if (ensemble::member_count(e) > 100000) {
    throw ScenarioError("/vary", std::to_string(ensemble::member_count(e)) + " members",
                        "at most 100000 members");
  }
  e.thresholds_m = read_thresholds(o, e.thresholds_m);
  e.threads_per_member = static_cast<int>(
      whole(o, "threads_per_member", 1, 1024, "OpenMP threads of each member").value_or(1));
  if (const auto jobs = whole(o, "jobs", 1, 1024, "members at once on this machine")) {
    e.jobs = static_cast<int>(*jobs);
  }
  if (o.find("run_time_limit") != nullptr) {
    e.run_time_limit_s = bounded(o, "run_time_limit", 0.0, true, 1e7,
                                 "the wall-clock seconds one member may take", 0.0);
  }
  if (const auto every =
          whole(o, "checkpoint_every", 1, 1000000, "output times between a member's checkpoints")) {
    e.checkpoint_every = static_cast<int>(*every);
  }
  std::filesystem::path default_folder = file.parent_path() / file.stem();
  e.folder = o.find("folder") == nullptr
                 ? default_folder
                 : path_of(o, "folder", "the folder of the members and products", base_dir);
  e.slurm = read_slurm(o);
  return e;
}

// A file name the base scene gives, made relative to the member's folder. A GDAL name that
// wraps a file (NETCDF:"dem.nc":elevation) has its file moved and the rest kept.
std::string rebased(const std::string& text, const std::filesystem::path& scene_dir,
                    const std::filesystem::path& member_folder) {
  const auto move = [&](const std::string& name) {
    const std::filesystem::path p(name);
    if (p.is_absolute()) return name;
    return (scene_dir / p).lexically_normal().lexically_relative(member_folder).string();
  };
  if (const auto wrapped = io::split_dataset_name(text)) {
    return wrapped->driver + ":\"" + move(wrapped->file) + "\"" + wrapped->rest;
  }
  return move(text);
}

// Every key of a scene that names a file: the readers' file_path() calls (load.cpp,
// load_water.cpp, load_flows.cpp, load_tsunami.cpp, load_rain.cpp). A new one must be added here,
// or members lose its file.
void rebase_files(json& scene, const std::filesystem::path& scene_dir,
                  const std::filesystem::path& member_folder) {
  const auto at = [&](json& holder, const char* key) {
    if (!holder.is_object()) return;
    const auto it = holder.find(key);
    if (it != holder.end() && it->is_string()) {
      *it = rebased(it->get<std::string>(), scene_dir, member_folder);
    }
  };
  const auto each = [&](const char* list, const char* key) {
    const auto it = scene.find(list);
    if (it == scene.end() || !it->is_array()) return;
    for (json& element : *it) at(element, key);
  };
  if (scene.contains("bed")) at(scene["bed"], "raster");
  if (scene.contains("friction")) {
    at(scene["friction"], "manning_n_raster");
    at(scene["friction"], "land_use_raster");
  }
  each("water", "depth_raster");
  each("inflow", "hydrograph_csv");
  each("sea_boundaries", "series_csv");
  // Rain is one object or an array of them, each naming files for its rate and for any of its
  // loss parameters.
  const auto rain_files = [&](json& rain) {
    if (!rain.is_object()) return;
    for (const char* key :
         {"rate_csv", "rate_raster", "rate_netcdf", "initial_loss_mm", "continuing_loss_mm_h"}) {
      at(rain, key);
    }
    if (const auto soil = rain.find("green_ampt"); soil != rain.end() && soil->is_object()) {
      for (const char* key : {"conductivity_mm_h", "suction_mm", "moisture_deficit"}) {
        at(*soil, key);
      }
    }
  };
  if (const auto rain = scene.find("rain"); rain != scene.end()) {
    if (rain->is_array()) {
      for (json& one : *rain) rain_files(one);
    } else {
      rain_files(*rain);
    }
  }
  // So are buildings.
  if (scene.contains("buildings")) at(scene["buildings"], "file");
  each("buildings", "file");
}

}  // namespace

ensemble::Ensemble parse_ensemble(const std::string& text, const std::filesystem::path& file) {
  // The shared readers speak of scenarios; an ensemble's messages say whose file is wrong.
  try {
    return read_ensemble(parse_json(text), std::filesystem::absolute(file).lexically_normal());
  } catch (const ScenarioError& e) {
    throw ScenarioError(e.json_path(), e.found(), e.expected(), "ensemble");
  }
}

ensemble::Ensemble load_ensemble(const std::filesystem::path& file) {
  std::string text;
  try {
    text = read_text_file(file, "a readable ensemble JSON file");
  } catch (const ScenarioError& e) {
    throw ScenarioError(e.json_path(), e.found(), e.expected(), "ensemble");
  }
  return parse_ensemble(text, file);
}

std::string member_scene(const ensemble::Ensemble& ensemble, const ensemble::Member& member,
                         const std::filesystem::path& member_folder) {
  json scene;
  try {
    scene = parse_json(ensemble.base_scene_text);
  } catch (const ScenarioError& e) {
    throw ScenarioError("/scene", "a scene that cannot be read: " + std::string(e.what()),
                        "a readable scenario JSON file", "ensemble");
  }
  for (std::size_t k = 0; k < ensemble.knobs.size(); ++k) {
    const ensemble::Knob& knob = ensemble.knobs[k];
    try {
      scene[json::json_pointer(knob.pointer)] = json::parse(member.values.at(k));
    } catch (const json::exception& e) {
      throw ScenarioError(element_path("/vary", k), literal(knob.pointer) + " (" + e.what() + ")",
                          "a pointer the base scene can take a value at", "ensemble");
    }
  }
  const std::filesystem::path folder = std::filesystem::absolute(member_folder).lexically_normal();
  rebase_files(scene, ensemble.base_scene.parent_path(), folder);
  if (!scene.contains("output") || !scene["output"].is_object()) scene["output"] = json::object();
  scene["output"]["path"] = kMemberResult;
  return scene.dump(2) + "\n";
}

}  // namespace swemps::scenario
