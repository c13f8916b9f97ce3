// swe-mps study: the runs of a sweep in child processes, a CSV row each, a Pareto front.
//
// Why processes and not threads: each run then has its own peak memory (the kernel's
// ru_maxrss of the child), a run that crashes or breaks down leaves the others running, and
// every run gets the OpenMP threads it is given. OpenMP's thread pool does not survive fork(),
// so the parent runs no OpenMP region at all: it reads files, forks and waits.

#include "swemps/cli/study_command.hpp"

#include <omp.h>
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <thread>
#include <variant>
#include <vector>

#include "swemps/cli/child_processes.hpp"
#include "swemps/cli/output_target.hpp"
#include "swemps/cli/progress.hpp"
#include "swemps/cli/run_command.hpp"
#include "swemps/cli/runs.hpp"
#include "swemps/cli/study_reference.hpp"
#include "swemps/cli/timing.hpp"
#include "swemps/io/flood_products.hpp"
#include "swemps/scenario/build.hpp"
#include "swemps/scenario/scenario.hpp"
#include "swemps/scenario/study_file.hpp"
#include "swemps/study/study.hpp"
#include "swemps/swe/simulation.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// What a run reports

// What a child sends back about its run. Counts are doubles so that every field can be
// unknown (NaN): a run that broke down has no errors, one that failed to build no steps.
struct RunRecord {
  std::string status = "failed";  // "ok", "breakdown", "failed" (or "timeout", set by the parent)
  std::string message;            // why it did not finish; empty when ok
  double particles_start = kNaN, particles_end = kNaN;
  double steps = kNaN, particle_steps = kNaN;
  double wall_s = kNaN;  // building the simulation and stepping it to the end time
  double fan_l1 = kNaN, fan_l2 = kNaN, fan_linf = kNaN, upstream_fan_l1 = kNaN;
  double front_x_m = kNaN, exact_front_x_m = kNaN;
  double relative_volume_change = kNaN;
};

// The record's numbers by name: the pipe's format and the table's columns both come from it.
struct NumberField {
  const char* name;
  double RunRecord::*member;
};
constexpr std::array kCountFields{
    NumberField{"particles_start", &RunRecord::particles_start},
    NumberField{"particles_end", &RunRecord::particles_end},
    NumberField{"steps", &RunRecord::steps},
    NumberField{"particle_steps", &RunRecord::particle_steps},
    NumberField{"wall_s", &RunRecord::wall_s},
};
constexpr std::array kErrorFields{
    NumberField{"fan_l1", &RunRecord::fan_l1},
    NumberField{"fan_l2", &RunRecord::fan_l2},
    NumberField{"fan_linf", &RunRecord::fan_linf},
    NumberField{"upstream_fan_l1", &RunRecord::upstream_fan_l1},
    NumberField{"front_x_m", &RunRecord::front_x_m},
    NumberField{"exact_front_x_m", &RunRecord::exact_front_x_m},
};
constexpr NumberField kVolumeField{"relative_volume_change", &RunRecord::relative_volume_change};

template <class Visit>
void for_each_number(Visit&& visit) {
  for (const auto& f : kCountFields) visit(f);
  for (const auto& f : kErrorFields) visit(f);
  visit(kVolumeField);
}

// The record as "name value" lines; the message last, made one line.
std::string encode(const RunRecord& r) {
  std::string text = "status " + r.status + "\n";
  for_each_number(
      [&](const NumberField& f) { text += fmt::format("{} {:.17g}\n", f.name, r.*f.member); });
  std::string message = r.message;
  std::replace(message.begin(), message.end(), '\n', ' ');
  return text + "message " + message + "\n";
}

// A record from encode()'s text; an empty or cut text leaves the fields it lacks unknown.
std::optional<RunRecord> decode(const std::string& text) {
  if (text.empty()) return std::nullopt;
  RunRecord r;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const auto space = line.find(' ');
    if (space == std::string::npos) continue;
    const std::string key = line.substr(0, space), value = line.substr(space + 1);
    if (key == "status") r.status = value;
    if (key == "message") r.message = value;
    for_each_number([&](const NumberField& f) {
      if (key == f.name) r.*f.member = std::strtod(value.c_str(), nullptr);
    });
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// One run, in the child

void record_errors(const study::RunMeasures& m, RunRecord& r) {
  r.fan_l1 = m.errors.fan_l1;
  r.fan_l2 = m.errors.fan_l2;
  r.fan_linf = m.errors.fan_linf;
  r.upstream_fan_l1 = m.errors.upstream_fan_l1;
  r.front_x_m = m.errors.front_x_m;
  r.exact_front_x_m = m.errors.exact_front_x_m;
}

void record_progress(const swe::Simulation& sim, RunRecord& r) {
  r.particles_end = static_cast<double>(sim.particles().fluid_count());
  r.steps = static_cast<double>(sim.steps());
  r.particle_steps = static_cast<double>(sim.particle_steps());
  r.relative_volume_change = sim.relative_volume_change();
}

// Runs `body`, which fills `r` and leaves it "ok" if it returns; a breakdown or any other
// failure is recorded with its message instead. Returns whether the run finished.
template <class Body>
bool recorded(RunRecord& r, Body&& body) {
  try {
    body();
    r.status = "ok";
    return true;
  } catch (const swe::SimulationError& e) {
    r.status = "breakdown";
    r.message = e.what();
  } catch (const std::exception& e) {
    r.status = "failed";
    r.message = e.what();
  }
  return false;
}

// The scene (knobs applied) from t = 0 to its end time, measured against the reference.
// A breakdown or failure is recorded with how far the run got.
RunRecord run_scene(const scenario::Scenario& scene, const study::Study& study) {
  RunRecord r;
  std::optional<swe::Simulation> sim;
  const auto start = Clock::now();
  const bool finished = recorded(r, [&] {
    sim.emplace(scenario::make_simulation(scene));
    r.particles_start = static_cast<double>(sim->particles().fluid_count());
    sim->advance_to(scene.end_time_s);
    sim->refresh();
    r.wall_s = seconds_since(start);
    record_progress(*sim, r);
    record_errors(study::measure(*sim, scene, std::get<study::RitterReference>(study.reference),
                                 study.profile_spacing_ratio),
                  r);
  });
  if (finished) return r;
  r.wall_s = seconds_since(start);
  if (sim) record_progress(*sim, r);
  return r;
}

// The scene run as `swe-mps run` runs it, into `file`: for a map reference, the run is
// measured by its written maximum depth and gauges, which the parent compares.
RunRecord run_scene_to_file(scenario::Scenario scene, const std::filesystem::path& scene_file,
                            const std::filesystem::path& file, const std::string& label) {
  RunRecord r;
  scene.output.path = file;
  const RunContext context{scene_file, label, false};
  const auto start = Clock::now();
  const bool finished = recorded(r, [&] {
    const RunReport report = run_swe(scene, context);
    r.wall_s = report.wall_s;
    r.particles_start = static_cast<double>(report.fluid_particles);
    r.particles_end = static_cast<double>(report.final_fluid_particles);
    r.steps = static_cast<double>(report.steps);
    r.particle_steps = static_cast<double>(report.particle_steps);
    r.relative_volume_change = report.relative_volume_change;
  });
  if (!finished) r.wall_s = seconds_since(start);
  return r;
}

// The child's whole life: never returns, and leaves through _exit so that nothing the parent
// set up (buffered output, atexit handlers, the partial table) is flushed or run twice.
[[noreturn]] void child_main(const scenario::Scenario& scene, const study::Study& study,
                             const std::filesystem::path& result, const std::string& label,
                             int threads, int result_fd, pid_t parent) {
  // A study stopped by a signal to its parent alone stops its runs too, rather than leaving
  // them to run on unseen. The parent may have gone before the request took effect.
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != parent) ::_exit(1);
  try {
    omp_set_num_threads(threads);
    spdlog::set_level(spdlog::level::warn);  // the parent reports each run
    write_all(result_fd,
              encode(result.empty() ? run_scene(scene, study)
                                    : run_scene_to_file(scene, study.scene, result, label)));
    ::close(result_fd);
    ::_exit(0);
  } catch (...) {
    ::_exit(1);
  }
}

// ---------------------------------------------------------------------------------------------
// The runs, in the parent

struct PlannedRun {
  study::RunKnobs knobs;
  scenario::Scenario scene;  // the base scene with the knobs applied
  double expected_cost = 1.0;
  std::filesystem::path result;  // map references: the run's netCDF file; else empty
};

// Particles go as spacing^-2 in the plane and steps as 1 / (spacing cfl) (eq 13): the relative
// cost the progress estimate weighs runs by, and the order they start in.
double expected_cost(const scenario::Scenario& scene) {
  const double spacing = study::finest_spacing(scene);
  if (!(spacing > 0.0)) return 1.0;
  return 1.0 / (spacing * spacing * spacing * scene.numerics.cfl);
}

// Where the runs of a study measured by maps keep their files: <table stem>-runs/ beside the
// table, one run-<k>.nc each (and its gauge table), for the user to look at after.
std::filesystem::path runs_folder(const std::filesystem::path& table) {
  std::filesystem::path folder = table;
  folder.replace_extension();
  folder += "-runs";
  return folder;
}

bool measured_by_maps(const study::Study& study) {
  return !std::holds_alternative<study::RitterReference>(study.reference);
}

std::vector<PlannedRun> plan_runs(const study::Study& study, const scenario::Scenario& base,
                                  const std::filesystem::path& table) {
  std::vector<PlannedRun> runs;
  std::vector<study::RunKnobs> expanded;
  try {
    expanded = study::expand(study.sweep, base.numerics.scheme);
  } catch (const std::invalid_argument& e) {
    throw scenario::ScenarioError("/sweep", e.what(),
                                  "knobs of the schemes the runs use (the \"scheme\" knob, "
                                  "or else the scene's)",
                                  "study");
  }
  for (const study::RunKnobs& knobs : expanded) {
    PlannedRun run{knobs, base, 1.0, {}};
    study::apply(knobs, run.scene);
    run.expected_cost = expected_cost(run.scene);
    if (measured_by_maps(study)) {
      run.result = runs_folder(table) / ("run-" + std::to_string(runs.size()) + ".nc");
    }
    runs.push_back(std::move(run));
  }
  return runs;
}

// Most expensive first, so that the last runs going are short ones and no core idles long
// while one big run finishes.
std::vector<std::size_t> start_order(const std::vector<PlannedRun>& runs) {
  std::vector<std::size_t> order(runs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return runs[a].expected_cost > runs[b].expected_cost;
  });
  return order;
}

// The run's child: it runs the scene in this program's own copy and writes its record into
// the pipe.
Child start_child(const PlannedRun& run, std::size_t index, const study::Study& study,
                  int threads) {
  const pid_t parent = ::getpid();
  const std::string label =
      "swe-mps study, run " + std::to_string(index) + " (" + study::describe(run.knobs) + ")";
  return fork_child(index, [&](int write_fd) {
    child_main(run.scene, study, run.result, label, threads, write_fd, parent);
  });
}

// What the wait status says about a child that sent no record.
std::string lost_child(int status) {
  return "the run's process " + wait_status_text(status) +
         (WIFSIGNALED(status) ? std::string() : std::string(" without a result"));
}

// A finished run: its record and the peak memory the kernel measured for its process; for a
// map reference, its measures (or why they could not be taken).
struct Row {
  RunRecord record;
  double peak_memory_mib = kNaN;
  std::optional<MapMeasures> map;
};

Row collect(const Child& child, int status, const rusage& usage, const std::string& output,
            std::optional<double> run_time_limit_s) {
  Row row;
  const auto record = decode(output);
  if (record) {
    row.record = *record;
  } else if (child.stopped && run_time_limit_s) {
    row.record.status = "timeout";
    row.record.message =
        fmt::format("stopped after the study's run time limit of {:g} s", *run_time_limit_s);
  } else {
    row.record.message = lost_child(status);
  }
  row.peak_memory_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
  return row;
}

// ---------------------------------------------------------------------------------------------
// The table

// What the table's columns are beyond the runs' knobs and costs: the fan's errors for an
// analytic reference; the maximum depth's and the gauge peaks' for a map reference.
struct TableLayout {
  bool maps = false;
  std::vector<std::string> gauges;  // map references: the gauges whose peaks are compared
};

std::vector<std::string> table_columns(const TableLayout& layout) {
  std::vector<std::string> columns{"run",      "spacing_m", "splitting_threshold", "scheme",
                                   "gradient", "kappa",     "dissipation",         "shifting",
                                   "cfl",      "alpha_e"};
  for (const auto& f : kCountFields) columns.emplace_back(f.name);
  columns.emplace_back("peak_memory_mib");
  if (layout.maps) {
    for (const char* name :
         {"max_depth_mad_m", "max_depth_bias_m", "within_0.5m", "wet_csi", "compared_cells"}) {
      columns.emplace_back(name);
    }
    for (const auto& g : layout.gauges) {
      const std::string name = io::column_name(g);
      columns.push_back(name + "_peak_m");
      columns.push_back(name + "_peak_error_m");
      columns.push_back(name + "_peak_time_error_s");
    }
  } else {
    for (const auto& f : kErrorFields) columns.emplace_back(f.name);
    columns.emplace_back("front_error_m");
  }
  columns.emplace_back(kVolumeField.name);
  columns.emplace_back("status");
  columns.emplace_back("message");
  if (layout.maps) columns.emplace_back("result");
  return columns;
}

// The map measures' fields, in table_columns' order; unknown (NaN) when not taken.
std::vector<std::string> map_fields(const TableLayout& layout,
                                    const std::optional<MapMeasures>& m) {
  std::vector<std::string> fields;
  const auto& d = m ? m->max_depth : study::MaxDepthComparison{kNaN, kNaN, kNaN, kNaN, 0};
  for (const double v :
       {d.mean_abs_difference_m, d.bias_m, d.within_half_metre, d.critical_success_index}) {
    fields.push_back(number_text(v));
  }
  fields.push_back(m ? std::to_string(d.compared_cells) : number_text(kNaN));
  for (std::size_t g = 0; g < layout.gauges.size(); ++g) {
    const bool known = m && g < m->gauges.size();
    for (const double v :
         {known ? m->gauges[g].peak_m : kNaN, known ? m->gauges[g].depth_error_m : kNaN,
          known ? m->gauges[g].time_error_s : kNaN}) {
      fields.push_back(number_text(v));
    }
  }
  return fields;
}

std::string table_line(const TableLayout& layout, std::size_t index, const PlannedRun& run,
                       const Row& row) {
  const auto& scene = run.scene;
  const RunRecord& r = row.record;
  const bool seed = scene.numerics.scheme == swe::SchemeKind::seed;
  std::vector<std::string> fields{
      std::to_string(index), number_text(study::finest_spacing(scene)),
      number_text(scene.splitting ? scene.splitting->area_ratio_threshold : kNaN),
      study::scheme_name(scene.numerics.scheme),
      // A scheme's own knobs are blank in the other scheme's rows.
      seed ? study::gradient_name(scene.numerics.gradient) : std::string(),
      seed ? std::string() : number_text(scene.numerics.kappa),
      seed ? std::string() : number_text(scene.numerics.dissipation),
      seed ? std::string() : number_text(scene.numerics.shifting), number_text(scene.numerics.cfl),
      seed ? number_text(scene.numerics.alpha_e) : std::string()};
  for (const auto& f : kCountFields) fields.push_back(number_text(r.*f.member));
  fields.push_back(number_text(row.peak_memory_mib));
  if (layout.maps) {
    for (auto& f : map_fields(layout, row.map)) fields.push_back(std::move(f));
  } else {
    for (const auto& f : kErrorFields) fields.push_back(number_text(r.*f.member));
    fields.push_back(number_text(r.front_x_m - r.exact_front_x_m));
  }
  fields.push_back(number_text(r.relative_volume_change));
  fields.push_back(r.status);
  fields.push_back(text_field(r.message));
  if (layout.maps) fields.push_back(text_field(run.result.string()));
  std::string line;
  for (std::size_t k = 0; k < fields.size(); ++k) line += (k > 0 ? "," : "") + fields[k];
  return line + "\n";
}

// The study's table, rewritten whole into <path>.partial as runs finish (rows in sweep order,
// finished ones only), so that an interrupted study keeps what it measured. finish() gives it
// its final name.
class StudyTable {
 public:
  StudyTable(std::filesystem::path path, const std::vector<PlannedRun>& runs, TableLayout layout)
      : path_(std::move(path)), runs_(runs), layout_(std::move(layout)), rows_(runs.size()) {
    partial_path_ = path_;
    partial_path_ += ".partial";
    write();  // an unwritable place is found before any run
  }

  void add(std::size_t run, Row row) {
    rows_[run] = std::move(row);
    write();
  }

  void finish() {
    std::error_code ec;
    std::filesystem::rename(partial_path_, path_, ec);
    if (ec) {
      throw OutputError("cannot rename '" + partial_path_.string() + "' to '" + path_.string() +
                        "': " + ec.message());
    }
  }

  const std::optional<Row>& row(std::size_t run) const { return rows_[run]; }
  const std::filesystem::path& path() const { return path_; }

 private:
  void write() const {
    std::string text;
    const auto columns = table_columns(layout_);
    for (std::size_t k = 0; k < columns.size(); ++k) text += (k > 0 ? "," : "") + columns[k];
    text += "\n";
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      if (rows_[i]) text += table_line(layout_, i, runs_[i], *rows_[i]);
    }
    errno = 0;
    std::FILE* file = std::fopen(partial_path_.c_str(), "w");
    if (file == nullptr) {
      throw OutputError("cannot create the file '" + partial_path_.string() +
                        "': " + (errno != 0 ? std::strerror(errno) : "unknown reason"));
    }
    const bool written = std::fputs(text.c_str(), file) >= 0;
    if (std::fclose(file) != 0 || !written) {
      throw OutputError("cannot write to '" + partial_path_.string() + "'");
    }
  }

  std::filesystem::path path_, partial_path_;
  const std::vector<PlannedRun>& runs_;
  TableLayout layout_;
  std::vector<std::optional<Row>> rows_;
};

// ---------------------------------------------------------------------------------------------
// Telling the user

std::string threads_text(int threads) {
  return std::to_string(threads) + (threads == 1 ? " thread" : " threads");
}

// "run 3/16 (spacing 0.1 m, mps): ok, 2.31 s, 45 MiB, fan L1 0.0213"
std::string finished_line(std::size_t run, std::size_t total, const PlannedRun& planned,
                          const Row& row) {
  const RunRecord& r = row.record;
  std::string line =
      fmt::format("run {}/{} ({}): {}", run + 1, total, study::describe(planned.knobs), r.status);
  if (!std::isnan(r.wall_s)) line += fmt::format(", {:.3g} s", r.wall_s);
  line += fmt::format(", {:.0f} MiB", row.peak_memory_mib);
  if (r.status == "ok" && !planned.result.empty()) {
    if (!row.map) return line + ", " + planned.result.filename().string();
    const auto& d = row.map->max_depth;
    return line + fmt::format(", max depth MAD {:.3f} m, bias {:+.3f} m, CSI {:.3f}",
                              d.mean_abs_difference_m, d.bias_m, d.critical_success_index);
  }
  if (r.status == "ok") return line + fmt::format(", fan L1 {:.4g}", r.fan_l1);
  // A breakdown's message is long (particle, position, time); the table has all of it.
  constexpr std::size_t kShown = 160;
  return line + ": " +
         (r.message.size() > kShown ? r.message.substr(0, kShown) + "..." : r.message);
}

void log_summary(const StudyTable& table, const std::vector<PlannedRun>& runs, double wall_s,
                 int jobs, int threads, bool maps) {
  std::size_t ok = 0, broke_down = 0, timed_out = 0, failed = 0;
  std::vector<study::CostError> points;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const Row& row = *table.row(i);
    const RunRecord& r = row.record;
    ok += r.status == "ok";
    broke_down += r.status == "breakdown";
    timed_out += r.status == "timeout";
    failed += r.status == "failed";
    const double error =
        maps ? (row.map ? row.map->max_depth.mean_abs_difference_m : kNaN) : r.fan_l1;
    points.push_back(r.status == "ok" ? study::CostError{r.wall_s, error}
                                      : study::CostError{kNaN, kNaN});
  }
  const char* error_name = maps ? "max depth MAD" : "fan L1";
  spdlog::info(
      "study: {} runs ({} ok, {} broke down, {} stopped at the time limit, {} failed) in {:.1f} s, "
      "{} at once, {} each",
      runs.size(), ok, broke_down, timed_out, failed, wall_s, jobs, threads_text(threads));
  spdlog::info(
      "Pareto front, wall time against {} (no other run is both faster and more "
      "accurate):",
      error_name);
  for (const std::size_t i : study::pareto_front(points)) {
    spdlog::info("  run {:>3}  {:9.3f} s  {} {:.4g}  ({})", i + 1, points[i].cost, error_name,
                 points[i].error, study::describe(runs[i].knobs));
  }
  if (broke_down + timed_out + failed > 0) {
    spdlog::warn("{} of {} runs did not finish; the table's status and message columns say why",
                 broke_down + timed_out + failed, runs.size());
  }
  spdlog::info("wrote {}", table.path().string());
}

// Kills the runs that have gone on past the limit; wait4 then reaps them like any other.
void stop_overdue(std::vector<Child>& going, std::optional<double> run_time_limit_s) {
  if (!run_time_limit_s) return;
  const auto now = std::chrono::steady_clock::now();
  for (Child& c : going) {
    if (c.stopped || std::chrono::duration<double>(now - c.started).count() <= *run_time_limit_s)
      continue;
    ::kill(c.pid, SIGKILL);
    c.stopped = true;
  }
}

// Runs every planned run, `jobs` at once, each child with `threads` OpenMP threads; rows go
// into the table as they finish.
// Measures a finished run's result against the reference; a result that cannot be read makes
// the run's row a failure that says so.
void measure_row(Row& row, const PlannedRun& run, const ReferenceMaps& reference,
                 double wet_depth_m) {
  try {
    row.map = measure_result(run.result, reference, wet_depth_m);
  } catch (const std::exception& e) {
    row.record.status = "failed";
    row.record.message =
        std::string("the run finished, but its result could not be measured: ") + e.what();
  }
}

// A map reference read before the runs, or none yet (an analytic one, or the finest run).
struct Measuring {
  std::optional<ReferenceMaps> reference;
  double wet_depth_m = 0.0;
};

void run_all(const std::vector<PlannedRun>& runs, const study::Study& study, int jobs, int threads,
             const Measuring& measuring, StudyTable& table, SweepProgress& progress) {
  std::size_t going_count = 0;
  PoolCalls calls;
  calls.start = [&](std::size_t run) {
    ++going_count;
    return start_child(runs[run], run, study, threads);
  };
  calls.between = [&](std::vector<Child>& going) {
    stop_overdue(going, study.run_time_limit_s);
    progress.tick(going.size());
    return true;
  };
  calls.ended = [&](const Child& child, int status, const rusage& usage,
                    const std::string& output) {
    --going_count;
    Row row = collect(child, status, usage, output, study.run_time_limit_s);
    if (measuring.reference && row.record.status == "ok") {
      measure_row(row, runs[child.task], *measuring.reference, measuring.wet_depth_m);
    }
    const std::string line = finished_line(child.task, runs.size(), runs[child.task], row);
    table.add(child.task, std::move(row));
    progress.finished(child.task, line, going_count);
  };
  run_pool(start_order(runs), jobs, calls);
}

// The finest run that finished, as the reference of all: its row's measures are its own (0).
void measure_against_finest(const std::vector<PlannedRun>& runs, double wet_depth_m,
                            StudyTable& table) {
  std::optional<std::size_t> finest;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (table.row(i)->record.status != "ok") continue;
    const double spacing = study::finest_spacing(runs[i].scene);
    if (!finest || spacing < study::finest_spacing(runs[*finest].scene)) finest = i;
  }
  if (!finest) {
    spdlog::warn("no run finished, so there is no finest run to measure the others against");
    return;
  }
  ReferenceMaps reference;
  try {
    reference = reference_from_result(runs[*finest].result);
  } catch (const std::exception& e) {
    spdlog::warn("the finest run's result cannot be read, so no run is measured: {}", e.what());
    return;
  }
  spdlog::info("the reference is run {} ({}), the finest that finished", *finest + 1,
               study::describe(runs[*finest].knobs));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (table.row(i)->record.status != "ok") continue;
    Row row = *table.row(i);
    measure_row(row, runs[i], reference, wet_depth_m);
    table.add(i, std::move(row));
  }
}

// The columns of a study's table, and the gauges a map reference compares.
TableLayout layout_for(const study::Study& study, const scenario::Scenario& base) {
  TableLayout layout;
  layout.maps = measured_by_maps(study);
  if (const auto* map = std::get_if<study::MapReference>(&study.reference)) {
    for (const auto& c : map->gauge_columns) layout.gauges.push_back(c.gauge);
  } else if (std::holds_alternative<study::FinestRunReference>(study.reference)) {
    for (const auto& g : base.output.gauges) layout.gauges.push_back(g.name);
  }
  return layout;
}

}  // namespace

// The command line is not used: the table is plain CSV, with no place for provenance.
void study(const Options& options, const std::string& /*command_line*/) {
  const study::Study definition = scenario::load_study(options.scenario);
  const scenario::Scenario base = scenario::load(definition.scene);
  if (base.model != scenario::Model::swe) {
    throw scenario::ScenarioError("/scene", "a scene with \"model\": \"ns\"",
                                  "a shallow-water scene (the study measures shallow-water runs)",
                                  "study");
  }
  const std::filesystem::path output =
      options.output ? output_option(*options.output) : definition.output;
  check_output_target(output);
  const std::vector<PlannedRun> runs = plan_runs(definition, base, output);
  Measuring measuring;
  measuring.wet_depth_m = definition.wet_depth_m.value_or(base.output.wet_depth_m);
  if (const auto* map = std::get_if<study::MapReference>(&definition.reference)) {
    measuring.reference = read_reference_maps(*map, base);
  }
  if (measured_by_maps(definition)) {
    std::error_code ec;
    std::filesystem::create_directories(runs_folder(output), ec);
    if (ec) {
      throw OutputError("cannot create the folder " + runs_folder(output).string() +
                        " for the runs' files: " + ec.message());
    }
  }
  const int cores = usable_cores();
  const int jobs = std::clamp(options.jobs > 0 ? options.jobs : definition.jobs.value_or(cores), 1,
                              static_cast<int>(runs.size()));
  const int threads = options.threads > 0 ? options.threads : std::max(1, cores / jobs);

  spdlog::info("study '{}': {} runs of scene '{}', {} at once, {} each, end time {} s",
               options.scenario.string(), runs.size(), base.name, jobs, threads_text(threads),
               base.end_time_s);
  StudyTable table(output, runs, layout_for(definition, base));
  std::vector<double> costs;
  for (const auto& run : runs) costs.push_back(run.expected_cost);
  SweepProgress progress(costs, options.verbosity != Verbosity::quiet);
  const auto start = Clock::now();
  run_all(runs, definition, jobs, threads, measuring, table, progress);
  progress.finish();
  if (std::holds_alternative<study::FinestRunReference>(definition.reference)) {
    measure_against_finest(runs, measuring.wet_depth_m, table);
  }
  table.finish();
  log_summary(table, runs, seconds_since(start), jobs, threads, measured_by_maps(definition));
}

}  // namespace swemps::cli
