// `swe-mps ensemble` end to end on a small dam break: members run here, one by one (as a
// scheduler runs them) and collected, a member that did not finish named and run again alone,
// a member stopped at the time limit, and products that count what the members' own results
// say, the same byte for byte however the members were run.

#include <netcdf.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/netcdf_values.hpp"
#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "swemps/cli/slurm_backend.hpp"

namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

const std::string cli = SWEMPS_CLI;

// Ritter's dam break at a coarse spacing: a member takes a fraction of a second.
std::string base_scene(double end_time) {
  return R"({"end_time": )" + std::to_string(end_time) + R"(,
    "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 4.65, "y_min": 0, "y_max": 1},
               "depth": 0.25, "spacing": 0.1}],
    "walls": [{"polyline": [[10, 0], [0, 0], [0, 1], [10, 1]], "condition": "slip"}],
    "output": {"path": "base.nc", "interval": 0.1, "grid": {"spacing": 0.05}}})";
}

// Three depths times two sampled Courant numbers: six members.
const char* kEnsemble = R"({"scene": "case/scenario.json",
  "vary": [{"pointer": "/water/0/depth", "name": "depth", "values": [0.1, 0.2, 0.3]},
           {"pointer": "/numerics/cfl", "name": "cfl", "range": [0.3, 0.6]}],
  "samples": 2, "seed": 5, "thresholds": [0.05, 0.15, 0.25], "jobs": 2})";

struct Fixture {
  swemps::testing::TempDir dir{"ensemble-cli"};
  fs::path file = dir.path() / "e.json";
  explicit Fixture(double end_time = 0.3, const std::string& extra = "") {
    fs::create_directories(dir.path() / "case");
    std::ofstream(dir.path() / "case" / "scenario.json") << base_scene(end_time);
    std::string text = kEnsemble;
    if (!extra.empty()) text.insert(text.rfind('}'), ", " + extra);
    std::ofstream(file) << text;
  }
  swemps::testing::CommandResult ensemble(const std::string& args) const {
    return swemps::testing::run_command(cli + " ensemble " + file.string() + " " + args);
  }
};

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::vector<std::string>> csv_rows(const fs::path& file) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(read(file));
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) fields.push_back(cell);
    rows.push_back(fields);
  }
  return rows;
}

std::vector<double> variable(const fs::path& file, const char* name) {
  int ncid = -1;
  REQUIRE(nc_open(file.c_str(), NC_NOWRITE, &ncid) == NC_NOERR);
  std::vector<double> values = swemps::testing::whole_variable(ncid, name);
  nc_close(ncid);
  return values;
}

std::vector<fs::path> products(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("ensemble", 0) == 0) out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Every product of `a` is in `b`, byte for byte.
void check_same_products(const fs::path& a, const fs::path& b) {
  const auto files = products(a);
  REQUIRE(files.size() == 1 + 3 * 2 + 2);  // netCDF, two maps per threshold, mean, envelope
  for (const fs::path& f : files) {
    INFO(f.filename());
    REQUIRE(fs::exists(b / f.filename()));
    CHECK(read(f) == read(b / f.filename()));
  }
}

}  // namespace

TEST_CASE("an ensemble runs here and its products count the members' own maxima",
          "[cli][ensemble]") {
  const Fixture f;
  const auto r = f.ensemble("-q");
  INFO(r.output);
  REQUIRE(r.status == 0);
  const fs::path folder = f.dir.path() / "e";
  const auto rows = csv_rows(folder / "members.csv");
  REQUIRE(rows.size() == 7);
  CHECK(rows[0][0] == "member");
  CHECK(rows[0][2] == "depth");
  CHECK(rows[0][3] == "cfl");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    CHECK(rows[i][0] == std::to_string(i - 1));
    CHECK(rows[i][4] == "ok");
    CHECK(rows[i][5] == "0");
  }
  CHECK(rows[1][2] == "0.1");
  CHECK(rows[6][2] == "0.3");
  // The two sampled Courant numbers, one in each half of the range, shared by every depth.
  const double cfl_a = std::stod(rows[1][3]), cfl_b = std::stod(rows[2][3]);
  CHECK(((cfl_a < 0.45) != (cfl_b < 0.45)));
  CHECK(rows[3][3] == rows[1][3]);
  CHECK(rows[6][3] == rows[2][3]);

  // Counts, probabilities, mean and envelope against the members' result files.
  const std::vector<double> thresholds{0.05, 0.15, 0.25};
  std::vector<std::vector<double>> maxima;
  for (int m = 0; m < 6; ++m) {
    maxima.push_back(variable(folder / ("member-" + std::to_string(m)) / "result.nc", "max_depth"));
  }
  const fs::path nc = folder / "ensemble.nc";
  const auto count = variable(nc, "exceedance_count");
  const auto probability = variable(nc, "exceedance_probability");
  const auto mean = variable(nc, "mean_max_depth");
  const auto envelope = variable(nc, "max_depth_envelope");
  const std::size_t cells = maxima[0].size();
  REQUIRE(count.size() == 3 * cells);
  REQUIRE(mean.size() == cells);
  std::size_t wet_cells_counted = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    double sum = 0.0, largest = 0.0;
    for (const auto& map : maxima) {
      REQUIRE(map[c] < 1e30);  // every cell of this grid has data
      sum += map[c];
      largest = std::max(largest, map[c]);
    }
    CHECK(mean[c] == Approx(sum / 6.0).margin(1e-6));
    CHECK(envelope[c] == Approx(largest).margin(1e-6));
    for (std::size_t j = 0; j < thresholds.size(); ++j) {
      double above = 0.0;
      for (const auto& map : maxima) above += map[c] > thresholds[j] ? 1.0 : 0.0;
      CHECK(count[j * cells + c] == above);
      CHECK(probability[j * cells + c] == Approx(above / 6.0).epsilon(1e-6));
      wet_cells_counted += above > 0.0 && above < 6.0;
    }
  }
  // The members differ: some cells are above a threshold in some members only.
  CHECK(wet_cells_counted > 0);
}

TEST_CASE("members run one by one and collected make the same products, byte for byte",
          "[cli][ensemble]") {
  const Fixture f;
  const fs::path here = f.dir.path() / "here", by_one = f.dir.path() / "one-by-one";
  REQUIRE(f.ensemble("-q -j 1 -o " + here.string()).status == 0);
  for (int m = 5; m >= 0; --m) {
    const auto r = f.ensemble("-q --member " + std::to_string(m) + " -o " + by_one.string());
    INFO(r.output);
    REQUIRE(r.status == 0);
  }
  CHECK(products(by_one).empty());
  const auto collected = f.ensemble("--collect -o " + by_one.string());
  INFO(collected.output);
  REQUIRE(collected.status == 0);
  check_same_products(here, by_one);

  SECTION("a member without a record is named, and --failed-only runs it alone") {
    fs::remove(by_one / "member-3" / "record.txt");  // as a run killed before it ended
    const auto missing = f.ensemble("--collect -o " + by_one.string());
    CHECK(missing.status == 5);
    CHECK_THAT(missing.output, Contains("1 of 6 members did not finish (member 3)"));
    CHECK_THAT(missing.output, Contains("--failed-only"));
    CHECK(csv_rows(by_one / "members.csv")[4][4] == "not_run");

    const auto untouched = fs::last_write_time(by_one / "member-0" / "result.nc");
    const auto again = f.ensemble("--failed-only -o " + by_one.string());
    INFO(again.output);
    REQUIRE(again.status == 0);
    CHECK_THAT(again.output, Contains("1 of 6 members to run here"));
    CHECK(fs::last_write_time(by_one / "member-0" / "result.nc") == untouched);
    check_same_products(here, by_one);
  }
  SECTION("--partial makes the products of the members that finished, and says so") {
    fs::remove(by_one / "member-0" / "record.txt");
    const auto partial = f.ensemble("--collect --partial -o " + by_one.string());
    CHECK(partial.status == 5);
    const auto members_used = variable(by_one / "ensemble.nc", "exceedance_probability");
    int ncid = -1;
    REQUIRE(nc_open((by_one / "ensemble.nc").c_str(), NC_NOWRITE, &ncid) == NC_NOERR);
    int combined = 0;
    CHECK(nc_get_att_int(ncid, NC_GLOBAL, "ensemble_members_combined", &combined) == NC_NOERR);
    nc_close(ncid);
    CHECK(combined == 5);
  }
}

TEST_CASE("a member past the time limit is stopped and recorded; the ensemble says so",
          "[cli][ensemble]") {
  // A minute simulated (600 maps) takes a second or more: five times the limit of 0.2 s.
  const Fixture f(60.0, R"("run_time_limit": 0.2)");
  const auto r = f.ensemble("-q");
  CHECK(r.status == 5);
  CHECK_THAT(r.output, Contains("6 of 6 members did not finish"));
  const auto rows = csv_rows(f.dir.path() / "e" / "members.csv");
  REQUIRE(rows.size() == 7);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    CHECK(rows[i][4] == "timeout");
    CHECK(rows[i][5] == "137");
  }
  CHECK(products(f.dir.path() / "e").empty());
  // One member alone exits as its run did: killed by SIGKILL, 128 + 9.
  const auto one = f.ensemble("-q --member 2");
  CHECK(one.status == 137);
  CHECK_THAT(one.output, Contains("member 2: timeout"));
}

TEST_CASE("an ensemble whose member scene is wrong stops before any member runs",
          "[cli][ensemble]") {
  const Fixture f;
  std::ofstream(f.file) << R"({"scene": "case/scenario.json",
    "vary": [{"pointer": "/numerics/cfl", "values": [0.5, 5]}]})";
  const auto r = f.ensemble("");
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Contains("scenario error at /numerics/cfl"));
  CHECK_THAT(r.output, Contains("in member 1"));
  CHECK_FALSE(fs::exists(f.dir.path() / "e" / "member-0" / "result.nc"));
  const auto modes = f.ensemble("--member 0 --collect");
  CHECK(modes.status == 2);
  CHECK_THAT(modes.output, Contains("give one at most"));
  const auto outside = f.ensemble("--member 7");
  CHECK(outside.status == 2);
  CHECK_THAT(outside.output, Contains("the ensemble has 2 members"));
}

TEST_CASE("SIGINT stops the members well; --failed-only runs them again", "[cli][ensemble]") {
  // Two members of a dam break sloshing in a closed tank for 20 s: 1-2 s each.
  swemps::testing::TempDir dir("ensemble-signal");
  fs::create_directories(dir.path() / "case");
  std::ofstream(dir.path() / "case" / "scenario.json") << R"({"end_time": 20,
    "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
    "water": [{"rectangle": {"x_min": 0, "x_max": 4.65, "y_min": 0, "y_max": 1},
               "depth": 0.25, "spacing": 0.05}],
    "walls": [{"polyline": [[10, 1], [10, 0], [0, 0], [0, 1], [10, 1]], "condition": "slip"}],
    "output": {"path": "base.nc", "interval": 5, "grid": {"spacing": 0.1}}})";
  const fs::path file = dir.path() / "e.json";
  std::ofstream(file) << R"({"scene": "case/scenario.json", "jobs": 2,
    "vary": [{"pointer": "/water/0/depth", "values": [0.2, 0.3]}]})";
  const fs::path log = dir.path() / "log", folder = dir.path() / "e";

  const pid_t pid = swemps::testing::start_program(cli, {"ensemble", file.string()}, log);
  // Once both runs are going (their first progress line is out), as a user's Ctrl-C.
  const auto going = [&](const char* member) {
    return read(folder / member / "run.out").find("progress:") != std::string::npos;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!(going("member-0") && going("member-1")) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGINT);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  INFO(read(log));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK_THAT(read(log),
             Contains("the ensemble stopped on SIGINT: 2 of 2 members have not finished"));
  const auto rows = csv_rows(folder / "members.csv");
  REQUIRE(rows.size() == 3);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    CHECK(rows[i][3] == "stopped");  // columns: member, folder, the knob, status
    CHECK(rows[i][4] == "143");      // each run stopped on the SIGTERM passed on to it
    // The run wrote what it had, as any run stopped by a signal does.
    CHECK(fs::exists(folder / rows[i][1] / "result.nc.partial"));
  }
  // Run again, each member goes on from the checkpoint its stopped run left, to the same
  // products as members run straight through.
  const auto again =
      swemps::testing::run_command(cli + " ensemble " + file.string() + " --failed-only -q");
  INFO(again.output);
  REQUIRE(again.status == 0);
  const auto resumed = csv_rows(folder / "members.csv");
  REQUIRE(resumed[0][12] == "resumed");
  for (std::size_t i = 1; i < resumed.size(); ++i) {
    CHECK(resumed[i][3] == "ok");
    CHECK(resumed[i][12] == "yes");
    CHECK_THAT(read(folder / resumed[i][1] / "run.out"), Contains("going on from checkpoint"));
  }
  const fs::path straight = dir.path() / "straight";
  REQUIRE(swemps::testing::run_command(cli + " ensemble " + file.string() + " -q -o " +
                                       straight.string())
              .status == 0);
  const auto made = products(straight);
  CHECK(made.size() == 1 + 4 * 2 + 2);  // the default four thresholds
  for (const fs::path& f : made) {
    INFO(f.filename());
    CHECK(read(f) == read(folder / f.filename()));
  }
}

TEST_CASE("a Slurm array names the members in ranges", "[cli][ensemble]") {
  using swemps::cli::array_ranges;
  CHECK(array_ranges({}).empty());
  CHECK(array_ranges({3}) == "3");
  CHECK(array_ranges({0, 1, 2, 3, 4, 5}) == "0-5");
  CHECK(array_ranges({0, 1, 2, 5, 7, 8}) == "0-2,5,7-8");
  CHECK(array_ranges({2, 4, 6}) == "2,4,6");
}

TEST_CASE("submitting without Slurm says so and exits 1", "[cli][ensemble]") {
  const Fixture f;
  // A PATH without sbatch, whatever this machine has.
  const auto r = swemps::testing::run_command("PATH=/nonexistent " + cli + " ensemble " +
                                              f.file.string() + " --submit");
  CHECK(r.status == 1);
  CHECK_THAT(r.output, Contains("sbatch was not found"));
  // The scripts are written, for a user who submits them by hand.
  CHECK(fs::exists(f.dir.path() / "e" / "slurm" / "member.sbatch"));
}
