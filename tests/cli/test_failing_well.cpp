// End-to-end tests of how `swe-mps run` fails well: a breakdown exits 3 and leaves the last
// good state in a readable OUTPUT.partial; SIGTERM and SIGINT stop the run after the current
// step with their own statuses, the file closed and readable; a run restarted from a
// checkpoint ends with the same file as one run straight through; a checkpoint that does not
// fit is refused with status 2.

#include <fcntl.h>
#include <netcdf.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "../support/netcdf_values.hpp"
#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/scenario/scenario.hpp"

namespace fs = std::filesystem;
using Catch::Contains;

namespace {

const std::string cli = SWEMPS_CLI;

// A dam break fed by an inflow and drained by an outflow line, with splitting: the effects
// whose state a checkpoint must carry. About a second on one thread.
constexpr const char* kDamScene = R"({
  "name": "dam", "end_time": 2.5,
  "domain": {"x_min": 0, "x_max": 12, "y_min": 0, "y_max": 1},
  "water": [{"rectangle": {"x_min": 0, "x_max": 4, "y_min": 0, "y_max": 1},
             "depth": 0.25, "spacing": 0.05}],
  "walls": [{"polyline": [[12, 0], [0, 0], [0, 1], [12, 1]]}],
  "splitting": {"threshold": 1.5},
  "inflow": [{"line": [[0.02, 0.05], [0.02, 0.95]], "hydrograph": [[0, 0.05]],
              "direction": [1, 0], "depth": 0.25}],
  "outflow": [{"line": [[9, 0], [9, 1]]}],
  "output": {"path": "dam.nc", "interval": 0.25, "grid": {"spacing": 0.1},
             "tsunami": {"still_level": 0, "arrival_rise": 0.01}}
})";

// Ritter's dam break with a time-step floor that the seed scheme's shrinking step crosses in
// step 4.
constexpr const char* kCollapseScene = R"({
  "name": "collapse", "end_time": 0.5,
  "numerics": {"scheme": "seed", "min_time_step": 0.027},
  "domain": {"x_min": 0, "x_max": 10, "y_min": 0, "y_max": 1},
  "water": [{"rectangle": {"x_min": 0, "x_max": 4.65, "y_min": 0, "y_max": 1},
             "depth": 0.25, "spacing": 0.1}],
  "walls": [{"polyline": [[10, 0], [0, 0], [0, 1], [10, 1]]}],
  "output": {"path": "collapse.nc", "interval": 0.1}
})";

// Water so thin that Manning's h^(4/3) underflows to 0: the friction of still water is 0 / 0.
constexpr const char* kThinScene = R"({
  "name": "thin", "end_time": 0.5,
  "domain": {"x_min": 0, "x_max": 2, "y_min": 0, "y_max": 1},
  "water": [{"rectangle": {"x_min": 0, "x_max": 1, "y_min": 0, "y_max": 1},
             "depth": 1e-300, "spacing": 0.1}],
  "friction": {"manning_n": 0.03},
  "output": {"path": "thin.nc", "interval": 0.1}
})";

fs::path write_scene(const fs::path& dir, const std::string& name, const char* text) {
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// One thread: on a busy machine a team of threads waits at every barrier for one that is
// descheduled, and these runs are small.
swemps::testing::CommandResult run(const std::string& args) {
  return swemps::testing::run_command(cli + " " + args + " -t 1");
}

// A netCDF file opened with netCDF-C, read-only.
class NcFile {
 public:
  explicit NcFile(const fs::path& path) {
    REQUIRE(nc_open(path.c_str(), NC_NOWRITE, &id_) == NC_NOERR);
  }
  ~NcFile() { nc_close(id_); }
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;

  std::size_t length(const char* dimension) const {
    int dim = -1;
    std::size_t n = 0;
    REQUIRE(nc_inq_dimid(id_, dimension, &dim) == NC_NOERR);
    REQUIRE(nc_inq_dimlen(id_, dim, &n) == NC_NOERR);
    return n;
  }
  std::string attribute(const char* name) const {
    std::size_t n = 0;
    if (nc_inq_attlen(id_, NC_GLOBAL, name, &n) != NC_NOERR) return {};
    std::string text(n, '\0');
    REQUIRE(nc_get_att_text(id_, NC_GLOBAL, name, text.data()) == NC_NOERR);
    return text;
  }
  std::vector<double> doubles(const char* name, std::size_t start, std::size_t count) const {
    int var = -1;
    REQUIRE(nc_inq_varid(id_, name, &var) == NC_NOERR);
    std::vector<double> values(count);
    if (count > 0) {
      REQUIRE(nc_get_vara_double(id_, var, &start, &count, values.data()) == NC_NOERR);
    }
    return values;
  }
  std::vector<double> all(const char* name, const char* dimension) const {
    return doubles(name, 0, length(dimension));
  }
  std::vector<double> times() const { return all("time", "time"); }
  // A variable of any shape, every value (x fastest for a map).
  std::vector<double> whole(const char* name) const {
    return swemps::testing::whole_variable(id_, name);
  }
  // A particle field at the last map time (contiguous ragged array).
  std::vector<double> last_particles(const char* name) const {
    const auto counts = all("particle_count", "time");
    std::size_t start = 0;
    for (std::size_t k = 0; k + 1 < counts.size(); ++k)
      start += static_cast<std::size_t>(counts[k]);
    return doubles(name, start, static_cast<std::size_t>(counts.back()));
  }

 private:
  int id_ = -1;
};

// The particles of the last map time and the whole series, bit for bit.
void require_same_end(const fs::path& a, const fs::path& b) {
  const NcFile fa(a), fb(b);
  CHECK(fa.times().back() == fb.times().back());
  for (const char* field : {"particle_x", "particle_y", "particle_u", "particle_v",
                            "particle_depth", "particle_volume", "particle_area"}) {
    INFO(field);
    CHECK(fa.last_particles(field) == fb.last_particles(field));
  }
  for (const char* series :
       {"series_time", "volume_in_domain", "volume_inflow", "volume_outflow"}) {
    INFO(series);
    CHECK(fa.all(series, "series_time") == fb.all(series, "series_time"));
  }
  // The maps were written (depth is time x y x, read whole).
  CHECK(!fa.whole("depth").empty());
  // The flood statistics went on from the checkpoint's as if never stopped.
  for (const char* map : {"max_depth", "time_of_max_depth", "max_speed", "max_hazard_rating",
                          "arrival_time", "inundation_duration", "hazard_class_uk",
                          "hazard_class_aidr", "max_surface_rise", "tsunami_arrival_time"}) {
    INFO(map);
    CHECK(fa.whole(map) == fb.whole(map));
  }
}

// Starts swe-mps with `args` (output to `log`), without waiting for it.
pid_t start(const std::vector<std::string>& args, const fs::path& log) {
  return swemps::testing::start_program(cli, args, log);
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Waits for the run's first progress line (a tenth of the run done; the log is not a terminal),
// then sends the signal and returns the exit status.
int stop_when_going(pid_t pid, const fs::path& log, int signal_number) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_text(log).find("progress:") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, signal_number);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  return WEXITSTATUS(status);
}

}  // namespace

TEST_CASE("a breakdown exits 3 and writes the last good state", "[cli][breakdown]") {
  swemps::testing::TempDir dir("failing-well");

  SECTION("a collapsing time step") {
    const auto scene = write_scene(dir.path(), "collapse.json", kCollapseScene);
    const auto r = run("run " + scene.string() + " -q");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Contains("swe-mps: the simulation broke down: the time step collapsed"));
    CHECK_THAT(r.output, Contains("for step 4 at t = "));
    CHECK_THAT(r.output, Contains("limited by particle "));
    CHECK_FALSE(fs::exists(dir.path() / "collapse.nc"));
    CHECK(fs::exists(dir.path() / "collapse.checkpoint"));
    const NcFile file(dir.path() / "collapse.nc.partial");
    CHECK(file.attribute("run_status") == "breakdown");
    CHECK_THAT(file.attribute("run_status_message"), Contains("the time step collapsed"));
    // t = 0, then the last good state, after step 3 and before the first output time.
    const auto times = file.times();
    REQUIRE(times.size() == 2);
    CHECK(times[1] > 0.05);
    CHECK(times[1] < 0.1);
    CHECK(file.last_particles("particle_x").size() > 400);
    // The log beside the result ends with how the run ended, as the terminal got it.
    const std::string log = read_text(dir.path() / "collapse.log");
    CHECK_THAT(log, Contains("[error] the simulation broke down: the time step collapsed"));
    CHECK_THAT(log, Contains("(exit status 3)\n"));
  }
  SECTION("a non-finite velocity") {
    const auto scene = write_scene(dir.path(), "thin.json", kThinScene);
    const auto r = run("run " + scene.string() + " -q");
    INFO(r.output);
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Contains("non-finite velocity (u, v) = "));
    CHECK_THAT(r.output,
               Contains("of particle 0 (at (0.05, 0.05) m when the step began), in step 1"));
    CHECK_THAT(r.output, Contains("the last good state, t = 0 s (step 0)"));
    const NcFile file(dir.path() / "thin.nc.partial");
    CHECK(file.attribute("run_status") == "breakdown");
    CHECK(file.times() == std::vector<double>{0.0});  // the starting state is the last good one
  }
}

TEST_CASE("SIGTERM and SIGINT stop the run with a readable file and a checkpoint to go on from",
          "[cli][signals]") {
  swemps::testing::TempDir dir("failing-well");
  const auto scene = write_scene(dir.path(), "dam.json", kDamScene).string();

  SECTION("SIGTERM, then a restart to the end") {
    const auto straight = run("run " + scene + " -q -o " + (dir.path() / "straight.nc").string());
    REQUIRE(straight.status == 0);
    const auto out = dir.path() / "stopped.nc";
    const pid_t pid = start({"run", scene, "-t", "1", "-o", out.string()}, dir.path() / "log");
    const int status = stop_when_going(pid, dir.path() / "log", SIGTERM);
    const std::string log = read_text(dir.path() / "log");
    INFO(log);
    REQUIRE(status == 143);
    CHECK_THAT(log, Contains("swe-mps: stopped by SIGTERM at t = "));
    CHECK_THAT(log, Contains("--restart " + (dir.path() / "stopped.checkpoint").string()));
    {
      const NcFile file(dir.path() / "stopped.nc.partial");
      CHECK(file.attribute("run_status") == "interrupted");
      CHECK(file.length("series_time") >= 1);
      CHECK(file.times().back() > 0.0);  // the state the run stopped at
      CHECK(file.times().back() < 2.5);
    }
    const auto restarted = run("run " + scene + " -q -o " + out.string() + " --restart " +
                               (dir.path() / "stopped.checkpoint").string());
    INFO(restarted.output);
    REQUIRE(restarted.status == 0);
    CHECK_FALSE(fs::exists(dir.path() / "stopped.nc.partial"));
    const NcFile file(out);
    CHECK(file.attribute("run_status") == "complete");
    CHECK_THAT(file.attribute("history"), Contains("--restart"));
    require_same_end(dir.path() / "straight.nc", out);
    // One log for the run, the restart's lines after the stopped run's.
    const std::string run_log = read_text(dir.path() / "stopped.log");
    const auto stopped_at = run_log.find("stopped by SIGTERM");
    const auto going_on_at = run_log.find("going on from checkpoint");
    CHECK(stopped_at != std::string::npos);
    CHECK(going_on_at != std::string::npos);
    CHECK(stopped_at < going_on_at);
  }
  SECTION("SIGINT") {
    const auto out = dir.path() / "interrupted.nc";
    const pid_t pid = start({"run", scene, "-t", "1", "-o", out.string()}, dir.path() / "log");
    const int status = stop_when_going(pid, dir.path() / "log", SIGINT);
    INFO(read_text(dir.path() / "log"));
    CHECK(status == 130);
    const NcFile file(dir.path() / "interrupted.nc.partial");
    CHECK(file.attribute("run_status") == "interrupted");
    CHECK(fs::exists(dir.path() / "interrupted.checkpoint"));
  }
}

TEST_CASE("a run killed after a checkpoint goes on from it to the same file", "[cli][checkpoint]") {
  swemps::testing::TempDir dir("failing-well");
  const auto scene = write_scene(dir.path(), "dam.json", kDamScene).string();
  const auto straight = dir.path() / "straight.nc";
  const auto r = run("run " + scene + " -q -o " + straight.string() + " --checkpoint-every 3");
  INFO(r.output);
  REQUIRE(r.status == 0);
  const auto checkpoint = dir.path() / "straight.checkpoint";
  REQUIRE(fs::exists(checkpoint));  // at t = 1.5 s: every 3rd output time before the end

  // A run killed between that checkpoint and its end leaves its file as .partial, with records
  // after the checkpoint: the restart writes them anew, and the same.
  const auto killed = dir.path() / "killed.nc";
  fs::copy_file(straight, dir.path() / "killed.nc.partial");
  fs::copy_file(checkpoint, dir.path() / "killed.checkpoint");
  const auto restarted = run("run " + scene + " -q -o " + killed.string() + " --restart " +
                             (dir.path() / "killed.checkpoint").string());
  INFO(restarted.output);
  REQUIRE(restarted.status == 0);
  require_same_end(straight, killed);
  const NcFile a(straight), b(killed);
  CHECK(a.times() == b.times());
  CHECK(a.all("particle_x", "particle_sample") == b.all("particle_x", "particle_sample"));
  CHECK(a.whole("max_depth") == b.whole("max_depth"));
  // The tsunami products are made at the end of the restarted run, as of a straight one.
  CHECK(fs::exists(dir.path() / "killed_inundation_line.gpkg"));
}

TEST_CASE("a checkpoint that does not fit is refused with status 2", "[cli][checkpoint]") {
  swemps::testing::TempDir dir("failing-well");
  const auto dam = write_scene(dir.path(), "dam.json", kDamScene).string();
  const auto thin = write_scene(dir.path(), "thin.json", kThinScene).string();
  REQUIRE(run("run " + thin + " -q").status == 3);  // leaves thin.checkpoint
  const auto thin_checkpoint = (dir.path() / "thin.checkpoint").string();

  const auto other_scene = run("run " + dam + " -q --restart " + thin_checkpoint);
  CHECK(other_scene.status == 2);
  CHECK_THAT(other_scene.output, Contains("swe-mps: cannot restart: the checkpoint"));
  CHECK_THAT(other_scene.output, Contains("was written for another scenario"));

  const auto missing = run("run " + dam + " -q --restart " + (dir.path() / "nope").string());
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Contains("no such file"));

  const auto not_checkpoint = run("run " + dam + " -q --restart " + dam);
  CHECK(not_checkpoint.status == 2);
  CHECK_THAT(not_checkpoint.output, Contains("is not a swe-mps checkpoint"));

  // The right checkpoint without the file it belongs to: nothing to go on writing.
  fs::remove(dir.path() / "thin.nc.partial");
  const auto no_output = run("run " + thin + " -q --restart " + thin_checkpoint);
  CHECK(no_output.status == 2);
  CHECK_THAT(no_output.output, Contains("cannot go on with the output the stopped run left"));

  const auto compare = run("compare " + dam + " --restart " + thin_checkpoint);
  CHECK(compare.status == 2);
  CHECK_THAT(compare.output, Contains("apply to 'run' only"));
}

TEST_CASE("a run that fails otherwise keeps the maps written before, closed with the reason",
          "[cli][breakdown]") {
  // Memory running out in the middle of a run, stood in for by the front observer, which the
  // run calls after every step: the same place in the time loop as splitting's allocations.
  const swemps::testing::TempDir dir("run-failure");
  const auto scene_file = write_scene(dir.path(), "dam.json", kDamScene);
  const auto scene = swemps::scenario::load(scene_file);
  swemps::cli::RunContext context{scene_file, "test", false};
  context.checkpoints = true;
  const auto fail_after_1_s = [](double t, double /*front*/) {
    if (t > 1.0) throw std::bad_alloc();
  };
  CHECK_THROWS_AS(swemps::cli::run_swe(scene, context, fail_after_1_s), std::bad_alloc);

  CHECK_FALSE(fs::exists(dir.path() / "dam.nc"));
  CHECK_FALSE(fs::exists(dir.path() / "dam.checkpoint"));  // the failed step is not trusted
  REQUIRE(fs::exists(dir.path() / "dam.nc.partial"));
  const NcFile file(dir.path() / "dam.nc.partial");
  CHECK(file.attribute("run_status") == "failed");
  CHECK_THAT(file.attribute("run_status_message"), Contains("bad_alloc"));
  // The maps of t = 0, 0.25, ..., 1, as written before the step past 1 s.
  const std::vector<double> times = file.times();
  CHECK(times == std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0});
  // The summary maps of the samples so far: the reservoir's 0.25 m, not the fill value.
  const std::vector<double> max_depth = file.whole("max_depth");
  const double deepest = *std::max_element(max_depth.begin(), max_depth.end());
  CHECK(deepest > 0.1);
  CHECK(deepest < 0.5);
}

namespace {

// A Navier-Stokes dam break in a 2D tank (100 fluid particles): it collapses, sloshes and
// settles. About 2 s on one thread, so that a signal after the first progress line lands
// mid-run.
constexpr const char* kNsTankScene = R"({
  "name": "tank", "end_time": 10,
  "model": "ns", "dimension": 2,
  "ns": {"spacing": 0.01},
  "domain": {"x_min": 0, "x_max": 0.4, "y_min": 0, "y_max": 0.1},
  "water": [{"rectangle": {"x_min": 0, "x_max": 0.1, "y_min": 0, "y_max": 0.1}, "depth": 0.1}],
  "output": {"path": "tank.nc", "interval": 0.5, "series_interval": 0.05,
             "gauges": [{"name": "wall foot", "x": 0.02, "y": 0.05}]}
})";

// A Navier-Stokes run writes no particles: the depth map of the last time, every series, the
// flood statistics and the series table, bit for bit (the table as text, to its last digit).
void require_same_ns_end(const fs::path& a, const fs::path& b) {
  const NcFile fa(a), fb(b);
  CHECK(fa.times().back() == fb.times().back());
  const auto depth_a = fa.whole("depth");
  const auto depth_b = fb.whole("depth");
  const std::size_t cells = depth_a.size() / fa.times().size();
  REQUIRE(cells > 0);
  REQUIRE(depth_b.size() >= cells);
  CHECK(std::vector<double>(depth_a.end() - static_cast<long>(cells), depth_a.end()) ==
        std::vector<double>(depth_b.end() - static_cast<long>(cells), depth_b.end()));
  for (const char* series : {"series_time", "volume_in_domain", "volume_outflow"}) {
    INFO(series);
    CHECK(fa.all(series, "series_time") == fb.all(series, "series_time"));
  }
  for (const char* map : {"max_depth", "time_of_max_depth", "max_speed", "arrival_time"}) {
    INFO(map);
    CHECK(fa.whole(map) == fb.whole(map));
  }
  const auto table = [](const fs::path& nc) { return read_text(swemps::cli::ns_series_path(nc)); };
  CHECK(!table(a).empty());
  CHECK(table(a) == table(b));
}

}  // namespace

TEST_CASE("a Navier-Stokes run stops on SIGTERM and goes on from its checkpoint to the same end",
          "[cli][signals][ns]") {
  swemps::testing::TempDir dir("failing-well-ns");
  const auto scene = write_scene(dir.path(), "tank.json", kNsTankScene).string();
  // The uninterrupted run every section compares with, made once: Catch runs the test case
  // from the top for each section, and under the sanitizers each run of the tank takes
  // seconds.
  static const swemps::testing::TempDir straight_dir("failing-well-ns-straight");
  const auto straight = straight_dir.path() / "straight.nc";
  static const auto r =
      run("run " + write_scene(straight_dir.path(), "tank.json", kNsTankScene).string() +
          " -q -o " + straight.string());
  INFO(r.output);
  REQUIRE(r.status == 0);

  SECTION("SIGTERM, then a restart to the end") {
    const auto out = dir.path() / "stopped.nc";
    const pid_t pid = start({"run", scene, "-t", "1", "-o", out.string()}, dir.path() / "log");
    const int status = stop_when_going(pid, dir.path() / "log", SIGTERM);
    const std::string log = read_text(dir.path() / "log");
    INFO(log);
    REQUIRE(status == 143);
    CHECK_THAT(log, Contains("swe-mps: stopped by SIGTERM at t = "));
    CHECK_THAT(log, Contains("--restart " + (dir.path() / "stopped.checkpoint").string()));
    CHECK(fs::exists(dir.path() / "stopped.checkpoint"));
    CHECK(fs::exists(dir.path() / "stopped.series.csv.partial"));
    {
      const NcFile file(dir.path() / "stopped.nc.partial");
      CHECK(file.attribute("run_status") == "interrupted");
      CHECK(file.length("series_time") >= 1);
      CHECK(file.times().back() > 0.0);  // the state the run stopped at
      CHECK(file.times().back() < 10.0);
    }
    const auto restarted = run("run " + scene + " -q -o " + out.string() + " --restart " +
                               (dir.path() / "stopped.checkpoint").string());
    INFO(restarted.output);
    REQUIRE(restarted.status == 0);
    CHECK_FALSE(fs::exists(dir.path() / "stopped.nc.partial"));
    CHECK_FALSE(fs::exists(dir.path() / "stopped.series.csv.partial"));
    const NcFile file(out);
    CHECK(file.attribute("run_status") == "complete");
    CHECK_THAT(file.attribute("history"), Contains("--restart"));
    require_same_ns_end(straight, out);
  }
  SECTION("--checkpoint-every, and a run killed after the checkpoint") {
    const auto every = dir.path() / "every.nc";
    const auto e = run("run " + scene + " -q -o " + every.string() + " --checkpoint-every 7");
    INFO(e.output);
    REQUIRE(e.status == 0);
    const auto checkpoint = dir.path() / "every.checkpoint";
    REQUIRE(fs::exists(checkpoint));  // at t = 7 s: the 14th output time
    require_same_ns_end(straight, every);

    // A run killed after that checkpoint leaves its files as .partial, with records after
    // it: the restart writes them anew, and the same.
    const auto killed = dir.path() / "killed.nc";
    fs::copy_file(every, dir.path() / "killed.nc.partial");
    fs::copy_file(swemps::cli::ns_series_path(every), dir.path() / "killed.series.csv.partial");
    fs::copy_file(checkpoint, dir.path() / "killed.checkpoint");
    const auto restarted = run("run " + scene + " -q -o " + killed.string() + " --restart " +
                               (dir.path() / "killed.checkpoint").string());
    INFO(restarted.output);
    REQUIRE(restarted.status == 0);
    require_same_ns_end(straight, killed);
    const NcFile a(straight), b(killed);
    CHECK(a.times() == b.times());
    CHECK(a.whole("depth") == b.whole("depth"));
  }
  SECTION("a checkpoint of another scene is refused") {
    const auto every = dir.path() / "every.nc";
    REQUIRE(run("run " + scene + " -q -o " + every.string() + " --checkpoint-every 7").status == 0);
    const auto other = write_scene(dir.path(), "other.json", kDamScene).string();
    const auto refused = run("run " + other + " -q -o " + every.string() + " --restart " +
                             (dir.path() / "every.checkpoint").string());
    CHECK(refused.status == 2);
    CHECK_THAT(refused.output, Contains("was written for another scenario"));
  }
}
