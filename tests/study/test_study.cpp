// Accuracy-cost studies: the sweep's product and its order, knobs set on a scene, the Pareto
// front, study files refused at the right JSON path, and `swe-mps study` end to end (rows as
// the sweep lists them, a breakdown recorded rather than stopping the study).

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../support/csv_table.hpp"
#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/scenario/study_file.hpp"
#include "swemps/study/study.hpp"

namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using swemps::scenario::ScenarioError;
using swemps::swe::GradientVariant;
using swemps::swe::SchemeKind;
using namespace swemps::study;

const std::string kRitter = std::string(SWEMPS_SOURCE_DIR) + "/cases/ritter/scenario.json";

// ---------------------------------------------------------------------------------------------
// Helpers

swemps::study::Study parse(const std::string& text) {
  return swemps::scenario::parse_study(text, "/studies", "/studies/default.csv");
}

// A study file around `sweep` (JSON text of the "sweep" object) and `extra` top-level keys.
std::string study_text(const std::string& sweep, const std::string& extra = "") {
  return R"({"scene": "scene.json", "reference": {"ritter": {"dam_x": 4.65, "depth": 0.25}},
             "sweep": )" +
         sweep + extra + "}";
}

struct Refusal {
  std::string label, text, path, expected;
};

void check_refused(const std::vector<Refusal>& cases) {
  for (const Refusal& c : cases) {
    INFO(c.label << ": " << c.text);
    try {
      parse(c.text);
      FAIL("accepted");
    } catch (const ScenarioError& e) {
      CHECK(e.json_path() == c.path);
      CHECK_THAT(std::string(e.what()), Contains("study error at " + c.path));
      CHECK_THAT(e.expected(), Contains(c.expected));
    }
  }
}

using swemps::testing::CsvRow;
using swemps::testing::number;
using swemps::testing::read_csv;
using Result = swemps::testing::CommandResult;

Result run(const std::string& command) { return swemps::testing::run_command(command); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// The sweep

TEST_CASE("expand gives the product of the axes, the first axis slowest", "[study]") {
  Sweep sweep;
  sweep.spacing_m = {0.2, 0.1};
  sweep.splitting = {SplittingChoice{}, SplittingChoice{1.5}};
  sweep.gradient = {GradientVariant::mps, GradientVariant::summation};
  sweep.alpha_e = {1.2};
  const auto runs = expand(sweep, SchemeKind::seed);
  REQUIRE(runs.size() == 8);
  std::size_t k = 0;
  for (const double spacing : {0.2, 0.1}) {
    for (const bool split : {false, true}) {
      for (const auto gradient : {GradientVariant::mps, GradientVariant::summation}) {
        INFO("run " << k);
        const RunKnobs& r = runs[k++];
        CHECK(r.spacing_m == spacing);
        REQUIRE(r.splitting.has_value());
        CHECK(r.splitting->area_ratio_threshold.has_value() == split);
        CHECK(r.gradient == gradient);
        CHECK_FALSE(r.cfl.has_value());  // not swept: the scene's
        CHECK(r.alpha_e == 1.2);
      }
    }
  }
  CHECK(runs[3].splitting->area_ratio_threshold == 1.5);
}

TEST_CASE("expand gives each scheme its own knobs and runs each combination once", "[study]") {
  Sweep sweep;
  sweep.scheme = {SchemeKind::seed, SchemeKind::conservative};
  sweep.gradient = {GradientVariant::mps, GradientVariant::summation};
  sweep.kappa = {1.2, 1.3};
  sweep.cfl = {0.5};
  const auto runs = expand(sweep, SchemeKind::conservative);
  // seed x {mps, summation} and conservative x {1.2, 1.3}: not 2 x 2 x 2.
  REQUIRE(runs.size() == 4);
  for (std::size_t k = 0; k < 2; ++k) {
    INFO("run " << k);
    CHECK(runs[k].scheme == SchemeKind::seed);
    CHECK(runs[k].gradient == sweep.gradient[k]);
    CHECK_FALSE(runs[k].kappa.has_value());
    CHECK(runs[k].cfl == 0.5);
    CHECK(runs[2 + k].scheme == SchemeKind::conservative);
    CHECK(runs[2 + k].kappa == sweep.kappa[k]);
    CHECK_FALSE(runs[2 + k].gradient.has_value());
    CHECK(runs[2 + k].cfl == 0.5);
  }
  CHECK(describe(runs[3]) == "conservative, kappa 1.3, cfl 0.5");

  // Without a scheme axis the scene's scheme decides which knobs apply.
  Sweep conservative_knobs;
  conservative_knobs.kappa = {1.2, 1.5};
  conservative_knobs.dissipation = {0.5};
  CHECK(expand(conservative_knobs, SchemeKind::conservative).size() == 2);
  // A swept knob that applies to no run is a mistake, not a silent no-op.
  CHECK_THROWS_WITH(expand(conservative_knobs, SchemeKind::seed),
                    Contains("\"kappa\", a knob of the conservative scheme"));
  Sweep seed_knobs;
  seed_knobs.alpha_e = {1.3};
  CHECK_THROWS_WITH(expand(seed_knobs, SchemeKind::conservative),
                    Contains("\"alpha_e\", a knob of the seed scheme"));
}

TEST_CASE("a sweep of no axis is one run of the scene as it is", "[study]") {
  const auto runs = expand(Sweep{}, SchemeKind::conservative);
  REQUIRE(runs.size() == 1);
  CHECK_FALSE(runs[0].spacing_m.has_value());
  CHECK_FALSE(runs[0].splitting.has_value());
  CHECK_FALSE(runs[0].gradient.has_value());
  CHECK(describe(runs[0]) == "the scene as it is");
}

TEST_CASE("apply sets the given knobs on a scene and leaves the rest", "[study]") {
  const auto original = swemps::scenario::load(kRitter);
  REQUIRE_FALSE(original.splitting.has_value());

  auto scene = original;
  apply(RunKnobs{}, scene);
  CHECK(scene.water[0].spacing_m == original.water[0].spacing_m);
  CHECK(scene.numerics.cfl == original.numerics.cfl);
  CHECK_FALSE(scene.splitting.has_value());

  RunKnobs knobs;
  knobs.spacing_m = 0.05;
  knobs.splitting = SplittingChoice{1.8};
  knobs.scheme = SchemeKind::seed;
  knobs.gradient = GradientVariant::summation;
  knobs.cfl = 0.3;
  knobs.alpha_e = 1.5;
  apply(knobs, scene);
  CHECK(scene.numerics.scheme == SchemeKind::seed);
  CHECK(scene.water[0].spacing_m == 0.05);
  CHECK(finest_spacing(scene) == 0.05);
  REQUIRE(scene.splitting.has_value());
  CHECK(scene.splitting->area_ratio_threshold == 1.8);
  CHECK(scene.splitting->alpha_s == swemps::splitting::SplittingSettings{}.alpha_s);
  CHECK(scene.numerics.gradient == GradientVariant::summation);
  CHECK(scene.numerics.cfl == 0.3);
  CHECK(scene.numerics.alpha_e == 1.5);
  CHECK(describe(knobs) ==
        "spacing 0.05 m, splitting 1.8, seed, summation, cfl 0.3, alpha_e 1.5");
  RunKnobs conservative;
  conservative.scheme = SchemeKind::conservative;
  conservative.kappa = 1.4;
  conservative.dissipation = 0.5;
  conservative.shifting = 0.0;
  apply(conservative, scene);
  CHECK(scene.numerics.scheme == SchemeKind::conservative);
  CHECK(scene.numerics.kappa == 1.4);
  CHECK(scene.numerics.dissipation == 0.5);
  CHECK(scene.numerics.shifting == 0.0);
  CHECK(describe(conservative) == "conservative, kappa 1.4, dissipation 0.5, shifting 0");

  // Splitting on keeps the scene's own settings but the threshold; off removes it.
  scene.splitting->alpha_s = 0.5;
  RunKnobs retune;
  retune.splitting = SplittingChoice{1.3};
  apply(retune, scene);
  CHECK(scene.splitting->alpha_s == 0.5);
  CHECK(scene.splitting->area_ratio_threshold == 1.3);
  RunKnobs off;
  off.splitting = SplittingChoice{};
  apply(off, scene);
  CHECK_FALSE(scene.splitting.has_value());
}

TEST_CASE("the Pareto front keeps the runs no other beats on both cost and error", "[study]") {
  const double nan = std::nan("");
  const std::vector<CostError> runs{
      {4.0, 0.01},  // 0: slowest, most accurate: on the front
      {1.0, 0.05},  // 1: fastest: on the front
      {2.0, 0.06},  // 2: beaten by 1
      {2.0, 0.03},  // 3: on the front
      {3.0, 0.03},  // 4: beaten by 3 (same error, slower)
      {nan, nan},   // 5: broke down
      {0.5, nan},   // 6: no error measured
  };
  CHECK(pareto_front(runs) == std::vector<std::size_t>{1, 3, 0});
  CHECK(pareto_front({}).empty());
}

// ---------------------------------------------------------------------------------------------
// Study files

TEST_CASE("a study file arrives field by field, paths taken from its folder", "[study]") {
  const auto s = parse(R"({
    "description": "two spacings",
    "scene": "case/scenario.json",
    "reference": {"ritter": {"dam_x": 25, "depth": 1, "reservoir_start_x": -1}},
    "sweep": {"spacing": [0.2, 0.1], "splitting": [null, 1.5], "scheme": ["seed"],
              "gradient": ["summation"], "kappa": [1.2, 1.4], "dissipation": [0, 1],
              "shifting": [0, 2], "cfl": [0.5, 2], "alpha_e": [1.3]},
    "profile_spacing_ratio": 8,
    "jobs": 3,
    "output": "out/table.csv"
  })");
  CHECK(s.scene == fs::path("/studies/case/scenario.json"));
  CHECK(s.output == fs::path("/studies/out/table.csv"));
  CHECK(std::get<swemps::study::RitterReference>(s.reference).dam_x_m == 25.0);
  CHECK(std::get<swemps::study::RitterReference>(s.reference).initial_depth_m == 1.0);
  CHECK(std::get<swemps::study::RitterReference>(s.reference).reservoir_start_x_m == -1.0);
  CHECK(s.sweep.spacing_m == std::vector<double>{0.2, 0.1});
  REQUIRE(s.sweep.splitting.size() == 2);
  CHECK_FALSE(s.sweep.splitting[0].area_ratio_threshold.has_value());
  CHECK(s.sweep.splitting[1].area_ratio_threshold == 1.5);
  CHECK(s.sweep.scheme == std::vector<SchemeKind>{SchemeKind::seed});
  CHECK(s.sweep.gradient == std::vector<GradientVariant>{GradientVariant::summation});
  CHECK(s.sweep.kappa == std::vector<double>{1.2, 1.4});
  CHECK(s.sweep.dissipation == std::vector<double>{0.0, 1.0});
  CHECK(s.sweep.shifting == std::vector<double>{0.0, 2.0});
  CHECK(s.sweep.cfl == std::vector<double>{0.5, 2.0});
  CHECK(s.profile_spacing_ratio == 8.0);
  CHECK(s.jobs == 3);
  // Every run is a seed run, so kappa, dissipation and shifting would apply to none.
  CHECK_THROWS(expand(s.sweep, SchemeKind::conservative));
  auto seed_only = s.sweep;
  seed_only.kappa.clear();
  seed_only.dissipation.clear();
  CHECK_THROWS(expand(seed_only, SchemeKind::conservative));  // shifting still
  seed_only.shifting.clear();
  CHECK(expand(seed_only, SchemeKind::conservative).size() == 8);

  const auto defaults = parse(study_text(R"({"spacing": [0.1]})"));
  CHECK(defaults.output == fs::path("/studies/default.csv"));
  CHECK(defaults.profile_spacing_ratio == 4.0);
  CHECK_FALSE(defaults.jobs.has_value());
  CHECK(std::get<swemps::study::RitterReference>(defaults.reference).reservoir_start_x_m == 0.0);
}

TEST_CASE("broken study files are refused at the JSON path of the problem", "[study]") {
  check_refused({
      {"unknown key", study_text(R"({"spacnig": [0.1]})"), "/sweep/spacnig",
       "did you mean \"spacing\"?"},
      {"unknown top-level key", study_text("{}", R"(, "job": 2)"), "/job", "one of the keys"},
      {"empty axis", study_text(R"({"spacing": []})"), "/sweep/spacing", "a non-empty array"},
      {"axis not an array", study_text(R"({"cfl": 0.5})"), "/sweep/cfl", "a non-empty array"},
      {"bad gradient name", study_text(R"({"gradient": ["mps", "sumation"]})"), "/sweep/gradient/1",
       "did you mean \"summation\"?"},
      {"negative spacing", study_text(R"({"spacing": [-0.1]})"), "/sweep/spacing/0",
       "a number in (0, 1000]"},
      {"spacing given twice", study_text(R"({"spacing": [0.1, 0.2, 0.1]})"), "/sweep/spacing/2",
       "each value once"},
      {"splitting threshold out of range", study_text(R"({"splitting": [null, 0.5]})"),
       "/sweep/splitting/1", "(1, 4]"},
      {"splitting as a word", study_text(R"({"splitting": ["off"]})"), "/sweep/splitting/0",
       "null (no splitting)"},
      {"alpha_e out of range", study_text(R"({"alpha_e": [0.5]})"), "/sweep/alpha_e/0", "[1, 3]"},
      {"bad scheme name", study_text(R"({"scheme": ["sed"]})"), "/sweep/scheme/0",
       "did you mean \"seed\"?"},
      {"kappa out of range", study_text(R"({"kappa": [3]})"), "/sweep/kappa/0", "[1, 2.5]"},
      {"negative dissipation", study_text(R"({"dissipation": [-1]})"), "/sweep/dissipation/0",
       "[0, 2]"},
      {"shifting out of range", study_text(R"({"shifting": [20]})"), "/sweep/shifting/0",
       "[0, 10]"},
      {"missing reference", R"({"scene": "s.json", "sweep": {}})", "/reference", "ritter"},
      {"reference without depth", R"({"scene": "s.json", "sweep": {},
         "reference": {"ritter": {"dam_x": 4.65}}})",
       "/reference/ritter/depth", "a number > 0"},
      {"reservoir past the dam", R"({"scene": "s.json", "sweep": {},
         "reference": {"ritter": {"dam_x": 4, "depth": 1, "reservoir_start_x": 5}}})",
       "/reference/ritter/reservoir_start_x", "< dam_x"},
      {"missing scene", R"({"reference": {"ritter": {"dam_x": 4, "depth": 1}}, "sweep": {}})",
       "/scene", "a path to the scenario file"},
      {"missing sweep", R"({"scene": "s.json", "reference": {"ritter": {"dam_x": 4, "depth": 1}}})",
       "/sweep", "an object of knob value lists"},
      {"jobs not whole", study_text("{}", R"(, "jobs": 1.5)"), "/jobs", "a whole number"},
      {"time limit of zero", study_text("{}", R"(, "run_time_limit": 0)"), "/run_time_limit",
       "(0, 10000000]"},
      {"profile coarser than the particles", study_text("{}", R"(, "profile_spacing_ratio": 0.5)"),
       "/profile_spacing_ratio", "[1, 64]"},
      {"not JSON", "{\"scene\": ", "", "valid JSON"},
  });
}

TEST_CASE("a study file that cannot be read names the file", "[study]") {
  try {
    swemps::scenario::load_study("/nonexistent/study.json");
    FAIL("read");
  } catch (const ScenarioError& e) {
    CHECK_THAT(std::string(e.what()), Contains("study error at /"));
    CHECK_THAT(std::string(e.what()), Contains("/nonexistent/study.json"));
  }
}

// ---------------------------------------------------------------------------------------------
// swe-mps study

TEST_CASE("swe-mps study runs every combination and tabulates cost and error", "[study]") {
  const swemps::testing::TempDir dir("study");
  std::ofstream(dir.path() / "study.json") << R"({
    "scene": ")" + kRitter + R"(",
    "reference": {"ritter": {"dam_x": 4.65, "depth": 0.25}},
    "sweep": {"spacing": [0.1], "scheme": ["seed", "conservative"],
              "gradient": ["mps", "summation"]},
    "jobs": 2
  })";
  const auto table = dir.path() / "table.csv";
  const auto r = run(std::string(SWEMPS_CLI) + " study " + (dir.path() / "study.json").string() +
                     " -o " + table.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_FALSE(fs::exists(table.string() + ".partial"));
  // Not a terminal: a plain line per finished run, then the summary.
  CHECK_THAT(r.output, Contains("run 1/3 (spacing 0.1 m, seed, mps): ok"));
  CHECK_THAT(r.output, Contains("run 2/3 (spacing 0.1 m, seed, summation): ok"));
  CHECK_THAT(r.output, Contains("run 3/3 (spacing 0.1 m, conservative): ok"));
  CHECK_THAT(r.output, Contains("Pareto front"));

  const auto rows = read_csv(table);
  REQUIRE(rows.size() == 3);
  CHECK(rows[0].at("gradient") == "mps");
  CHECK(rows[1].at("gradient") == "summation");
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(rows[k].at("scheme") == "seed");
    CHECK(rows[k].at("kappa").empty());  // the conservative scheme's knobs
    CHECK(rows[k].at("dissipation").empty());
    CHECK(rows[k].at("shifting").empty());
    CHECK(number(rows[k], "alpha_e") == 1.3);
  }
  // And the seed scheme's knobs are blank in the conservative run's row.
  CHECK(rows[2].at("scheme") == "conservative");
  CHECK(rows[2].at("gradient").empty());
  CHECK(rows[2].at("alpha_e").empty());
  CHECK(number(rows[2], "kappa") == 1.3);
  CHECK(number(rows[2], "dissipation") == 1.0);
  CHECK(number(rows[2], "shifting") == 2.0);
  for (const CsvRow& row : rows) {
    CHECK(row.at("status") == "ok");
    CHECK(row.at("message").empty());
    CHECK(number(row, "spacing_m") == 0.1);
    CHECK(row.at("splitting_threshold") == "nan");  // the scene splits nothing
    CHECK(number(row, "cfl") == 0.5);
    CHECK(number(row, "particles_start") == 470);
    CHECK(number(row, "particle_steps") > 0);
    CHECK(number(row, "steps") > 0);
    CHECK(number(row, "wall_s") > 0);
    CHECK(number(row, "peak_memory_mib") > 0);
    CHECK(number(row, "fan_l1") > 0);
    CHECK(number(row, "fan_l1") < 0.2);
    CHECK(number(row, "fan_l2") >= number(row, "fan_l1"));
    CHECK(number(row, "fan_linf") >= number(row, "fan_l2"));
    CHECK(number(row, "exact_front_x_m") == Approx(4.65 + 2 * std::sqrt(9.81 * 0.25) * 0.5));
    CHECK(number(row, "front_error_m") ==
          Approx(number(row, "front_x_m") - number(row, "exact_front_x_m")));
    CHECK(std::abs(number(row, "relative_volume_change")) < 1e-12);
  }
}

TEST_CASE("a run that breaks down is a row of the study, not its end", "[study]") {
  // Even a Courant number of 50 does not break the dam break down (the huge steps smear the
  // wave, measured): a time-step floor above what cfl 0.05 gives does, at the first step.
  const swemps::testing::TempDir dir("study-breakdown");
  std::ifstream in(kRitter);
  std::stringstream scene;
  scene << in.rdbuf();
  std::string text = scene.str();
  const std::string numerics = "\"numerics\": {";
  text.replace(text.find(numerics), numerics.size(), numerics + "\"min_time_step\": 0.005, ");
  std::ofstream(dir.path() / "scene.json") << text;
  std::ofstream(dir.path() / "study.json") << R"({
    "scene": "scene.json",
    "reference": {"ritter": {"dam_x": 4.65, "depth": 0.25}},
    "sweep": {"cfl": [0.05, 0.5]},
    "jobs": 1,
    "output": "table.csv"
  })";
  const auto r = run(std::string(SWEMPS_CLI) + " study " + (dir.path() / "study.json").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Contains("1 of 2 runs did not finish"));
  const auto rows = read_csv(dir.path() / "table.csv");
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].at("status") == "breakdown");
  CHECK_THAT(rows[0].at("message"), Contains("time step collapsed"));
  CHECK(rows[0].at("fan_l1") == "nan");
  CHECK(number(rows[0], "particles_start") == 470);
  CHECK(number(rows[0], "peak_memory_mib") > 0);
  CHECK(rows[1].at("status") == "ok");
  CHECK(number(rows[1], "fan_l1") < 0.2);
}

TEST_CASE("a run past the study's time limit is stopped and recorded", "[study]") {
  // The 10 m dam break at 1 cm spacing (46,500 particles) takes tens of seconds; the limit
  // stops it after a few, and the coarse run beside it finishes within them even sanitized on
  // a busy machine (0.3 s was too tight for that).
  const swemps::testing::TempDir dir("study-timeout");
  std::ofstream(dir.path() / "study.json") << R"({
    "scene": ")" + kRitter + R"(",
    "reference": {"ritter": {"dam_x": 4.65, "depth": 0.25}},
    "sweep": {"spacing": [0.01, 0.1]},
    "jobs": 2,
    "run_time_limit": 3,
    "output": "table.csv"
  })";
  const auto r = run(std::string(SWEMPS_CLI) + " study " + (dir.path() / "study.json").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  const auto rows = read_csv(dir.path() / "table.csv");
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].at("status") == "timeout");
  CHECK_THAT(rows[0].at("message"), Contains("run time limit of 3 s"));
  CHECK(rows[0].at("fan_l1") == "nan");
  CHECK(rows[1].at("status") == "ok");
}

TEST_CASE("swe-mps study refuses a broken study file with exit status 2", "[study]") {
  const swemps::testing::TempDir dir("study-broken");
  std::ofstream(dir.path() / "study.json") << study_text(R"({"gradient": ["mpss"]})");
  const auto r = run(std::string(SWEMPS_CLI) + " study " + (dir.path() / "study.json").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Contains("study error at /sweep/gradient/0"));
  CHECK(run(std::string(SWEMPS_CLI) + " study").status == 2);
  CHECK_THAT(run(std::string(SWEMPS_CLI) + " --help").output, Contains("swe-mps study STUDY.json"));
  CHECK(run(std::string(SWEMPS_CLI) + " study x.json --jobs 0").status == 2);
}
