// The ensemble on a real Slurm cluster (CTest label slurm; tools/slurm-one-node starts a
// one-node cluster on this machine first, and that test fails if its daemons cannot start):
// six members submitted as a job array with a collection job after it, one member cancelled
// while it runs, the collection naming it, the member resubmitted alone and going on from the
// checkpoint its cancelled run left, and products that match a local run of the same ensemble
// byte for byte.

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using swemps::testing::run_command;

const std::string cli = SWEMPS_CLI;

// A dam break sloshing in a closed 10 m tank for 40 s: 3-4 s a member, long enough to cancel
// one while it runs.
const char* kScene = R"({"end_time": 40,
  "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
  "water": [{"rectangle": {"x_min": 0, "x_max": 4.65, "y_min": 0, "y_max": 1},
             "depth": 0.25, "spacing": 0.05}],
  "walls": [{"polyline": [[10, 1], [10, 0], [0, 0], [0, 1], [10, 1]], "condition": "slip"}],
  "output": {"path": "base.nc", "interval": 5, "grid": {"spacing": 0.1}}})";

const char* kEnsemble = R"({"scene": "case/scenario.json",
  "vary": [{"pointer": "/water/0/depth", "values": [0.15, 0.25, 0.35]},
           {"pointer": "/friction/manning_n", "range": [0.01, 0.03]}],
  "samples": 2, "seed": 2026, "thresholds": [0.05, 0.2], "jobs": 2,
  "slurm": {"partition": "debug", "time": "10:00", "max_running": 2}})";

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Waits until `done()` or `seconds` have passed; false on the latter.
template <class Done>
bool wait_for(Done done, double seconds) {
  const auto start = std::chrono::steady_clock::now();
  while (!done()) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return true;
}

// The last submission's job ids, from <folder>/slurm/submitted.txt:
// "array 101 members 0-5%2 collect 102".
struct Submission {
  std::string array, members, collect;
};
Submission last_submission(const fs::path& folder) {
  std::istringstream lines(read(folder / "slurm" / "submitted.txt"));
  std::string line, last;
  while (std::getline(lines, line)) {
    if (!line.empty()) last = line;
  }
  std::istringstream words(last);
  std::string word;
  Submission s;
  words >> word >> s.array >> word >> s.members >> word >> s.collect;
  return s;
}

// Neither job is pending or running any more.
bool jobs_ended(const Submission& s) {
  const auto r = run_command("squeue -h -o %i -j " + s.array + "," + s.collect);
  return r.output.find_first_not_of(" \n") == std::string::npos ||
         r.output.find("Invalid job id") != std::string::npos;
}

std::vector<fs::path> products(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().filename().string().rfind("ensemble", 0) == 0) out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("an ensemble on Slurm: a member cancelled, resubmitted alone, products as local",
          "[slurm][ensemble]") {
  const swemps::testing::TempDir dir("slurm-ensemble");
  fs::create_directories(dir.path() / "case");
  std::ofstream(dir.path() / "case" / "scenario.json") << kScene;
  const fs::path file = dir.path() / "e.json";
  std::ofstream(file) << kEnsemble;
  const fs::path local = dir.path() / "local", cluster = dir.path() / "cluster";
  const std::string ensemble = cli + " ensemble " + file.string();

  const auto here = run_command(ensemble + " -q -o " + local.string());
  INFO(here.output);
  REQUIRE(here.status == 0);

  // Submit; cancel member 2 while its run is going.
  const auto submitted = run_command(ensemble + " --submit --memory 1G -o " + cluster.string());
  INFO(submitted.output);
  REQUIRE(submitted.status == 0);
  const Submission first = last_submission(cluster);
  CHECK(first.members == "0-5%2");
  const std::string script = read(cluster / "slurm" / "member.sbatch");
  CHECK_THAT(script, Contains("#SBATCH --partition=debug"));
  CHECK_THAT(script, Contains("#SBATCH --time=10:00"));
  CHECK_THAT(script, Contains("#SBATCH --cpus-per-task=1"));
  CHECK_THAT(script, Contains("#SBATCH --mem=1G"));  // from the command line
  // Once its run has stepped a tenth of the way (its first progress line), so that it has a
  // state to write when the cancel's SIGTERM comes.
  REQUIRE(wait_for(
      [&] { return read(cluster / "member-2" / "run.out").find("progress:") != std::string::npos; },
      120.0));
  const auto cancel = run_command("scancel " + first.array + "_2");
  INFO(cancel.output);
  REQUIRE(cancel.status == 0);
  REQUIRE(wait_for([&] { return jobs_ended(first); }, 300.0));

  // The collection ran after every task, named member 2, and made no products.
  const std::string collected = read(cluster / "slurm" / ("collect-" + first.collect + ".out"));
  INFO(collected);
  CHECK_THAT(collected, Contains("1 of 6 members did not finish (member 2)"));
  CHECK(products(cluster).empty());
  const std::string table = read(cluster / "members.csv");
  CHECK_THAT(table, Contains(first.array + "_0"));
  CHECK_THAT(table, Contains(first.array + "_5"));

  // Resubmitted: member 2 alone, then the products.
  const auto again = run_command(ensemble + " --submit --failed-only -o " + cluster.string());
  INFO(again.output);
  REQUIRE(again.status == 0);
  const Submission second = last_submission(cluster);
  CHECK(second.members == "2%2");
  REQUIRE(wait_for([&] { return jobs_ended(second); }, 300.0));
  const std::string recollected = read(cluster / "slurm" / ("collect-" + second.collect + ".out"));
  INFO(recollected);
  CHECK_THAT(recollected, Contains("from 6 of 6 members"));
  CHECK_THAT(read(cluster / "members.csv"), Contains(second.array + "_2"));
  // scancel's SIGTERM stopped the run well, with a checkpoint: the member went on from it.
  CHECK_THAT(read(cluster / "member-2" / "run.out"), Contains("going on from checkpoint"));

  const auto made_here = products(local);
  REQUIRE(made_here.size() == 1 + 2 * 2 + 2);
  for (const fs::path& f : made_here) {
    INFO(f.filename());
    REQUIRE(fs::exists(cluster / f.filename()));
    CHECK(read(f) == read(cluster / f.filename()));
  }
}
