// End-to-end tests of the swe-mps executable: exit statuses, messages, and that its output
// opens in the netCDF and GDAL command-line tools.

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Result {
  int status;
  std::string output;  // stdout and stderr together
};

Result run(const std::string& command) {
  Result r{-1, {}};
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

bool have(const std::string& tool) {
  return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0;
}

fs::path fresh_dir(const std::string& name) {
  const auto dir =
      fs::temp_directory_path() / ("swemps-cli-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::string cli = SWEMPS_CLI;
const std::string ritter = std::string(SWEMPS_SOURCE_DIR) + "/cases/ritter/scenario.json";

}  // namespace

TEST_CASE("--help and --version", "[cli]") {
  const auto help = run(cli + " --help");
  CHECK(help.status == 0);
  CHECK_THAT(help.output, Catch::Contains("swe-mps run SCENARIO.json"));
  const auto version = run(cli + " --version");
  CHECK(version.status == 0);
  CHECK_THAT(version.output, Catch::StartsWith("swe-mps "));
}

TEST_CASE("bad command lines exit 2 with one clear message", "[cli]") {
  for (const std::string args :
       {"", "fly x.json", "run", "run a.json --threads zero", "run a.json --bogus"}) {
    const auto r = run(cli + " " + args);
    INFO(args << " -> " << r.output);
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::StartsWith("swe-mps: "));
  }
}

TEST_CASE("a broken scenario exits 2 naming the JSON path", "[cli]") {
  const auto dir = fresh_dir("bad");
  std::ofstream(dir / "scenario.json")
      << R"({"end_time": 1, "domain": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1}, "dpeth": 0.1, "spacing": 0.1}]})";
  const auto r = run(cli + " run " + (dir / "scenario.json").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("/water/0/dpeth"));
  CHECK_THAT(r.output, Catch::Contains("did you mean \"depth\""));
  CHECK_THAT(r.output, !Catch::Contains("terminate"));
  const auto missing = run(cli + " run " + (dir / "nope.json").string());
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Catch::Contains("cannot read file"));
  fs::remove_all(dir);
}

TEST_CASE("an output folder that does not exist exits 4 and leaves nothing behind", "[cli]") {
  const auto dir = fresh_dir("noout");
  const auto r = run(cli + " run " + ritter + " -q -o " + (dir / "missing" / "out.nc").string());
  CHECK(r.status == 4);
  CHECK_THAT(r.output, Catch::Contains("out.nc"));
  CHECK_FALSE(fs::exists(dir / "missing"));
  fs::remove_all(dir);
}

TEST_CASE("the Ritter case runs end to end and its file opens in ncdump and gdalinfo", "[cli]") {
  const auto dir = fresh_dir("ritter");
  const auto out = dir / "ritter.nc";
  const auto r = run(cli + " run " + ritter + " --threads 2 -o " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
  // Not a terminal: plain progress lines, then the closing summary.
  CHECK_THAT(r.output, Catch::Contains("progress: 100.0%"));
  CHECK_THAT(r.output, Catch::Contains("particle-steps/s"));
  CHECK_THAT(r.output, Catch::Contains("relative change"));
  CHECK_THAT(r.output, Catch::Contains("effect 'domain outflow'"));
  if (have("ncdump")) {
    const auto dump = run("ncdump -h " + out.string());
    CHECK(dump.status == 0);
    CHECK_THAT(dump.output, Catch::Contains(":Conventions = \"CF-1.8\""));
    CHECK_THAT(dump.output, Catch::Contains("time = UNLIMITED ; // (6 currently)"));
  } else {
    WARN("ncdump not installed: skipped");
  }
  if (have("gdalinfo")) {
    const auto info = run("gdalinfo NETCDF:\"" + out.string() + "\":depth");
    CHECK(info.status == 0);
    CHECK_THAT(info.output, Catch::Contains("Size is 500, 50"));
  } else {
    WARN("gdalinfo not installed: skipped");
  }
  fs::remove_all(dir);
}
