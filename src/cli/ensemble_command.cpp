// swe-mps ensemble: plan the members, run them (here, or through a scheduler), collect them.
//
// Every backend runs a member the same way: `swe-mps ensemble FILE --member N`, which writes
// the member's scene, runs `swe-mps run` on it in a child process and records how it ended
// (ensemble_member.hpp). The local backend starts those processes itself, --jobs at once; a
// Slurm job array starts one per array task (slurm_backend.hpp). The collection reads only the
// members' folders, so it gives the same products whoever ran them.

#include "swemps/cli/ensemble_command.hpp"

#include <fcntl.h>
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <vector>

#include "swemps/cli/child_processes.hpp"
#include "swemps/cli/ensemble_member.hpp"
#include "swemps/cli/output_target.hpp"
#include "swemps/cli/progress.hpp"
#include "swemps/cli/run_command.hpp"
#include "swemps/cli/slurm_backend.hpp"
#include "swemps/cli/stop_signals.hpp"
#include "swemps/cli/timing.hpp"
#include "swemps/io/ensemble_products.hpp"
#include "swemps/scenario/ensemble_file.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kMembersTable = "members.csv";
constexpr const char* kProductsStem = "ensemble";

// "peak 2000, manning_n 0.035": a member's knobs, for messages.
std::string describe(const ensemble::Ensemble& e, const ensemble::Member& m) {
  std::string text;
  for (std::size_t k = 0; k < e.knobs.size(); ++k) {
    text += (k > 0 ? ", " : "") + e.knobs[k].name + " " + m.values[k];
  }
  return text;
}

bool finished(const std::optional<MemberRecord>& record) {
  return record && record->status == "ok";
}

// ---------------------------------------------------------------------------------------------
// Collecting

// A member as the table and the products see it.
struct CollectedMember {
  std::optional<MemberRecord> record;
  std::string status, message;  // the record's, or why the member cannot be combined
  std::optional<io::MemberResult> result;
  double max_depth_m = kNaN, flooded_area_m2 = kNaN;
};

CollectedMember collect_member(const ensemble::Ensemble& e, std::size_t index) {
  const std::filesystem::path folder = member_folder(e, index);
  CollectedMember c;
  c.record = read_member_record(folder);
  if (!c.record) {
    c.status = "not_run";
    c.message =
        "no record: the member has not run, or its run was killed before it ended (a "
        "scheduler's time limit, a lost node)";
    return c;
  }
  c.status = c.record->status;
  c.message = c.record->message;
  if (c.status != "ok") return c;
  try {
    c.result = io::read_member_result(folder / scenario::kMemberResult);
  } catch (const std::exception& error) {
    c.status = "failed";
    c.message = std::string("its result cannot be read: ") + error.what();
    return c;
  }
  const auto& map = c.result->max_depth;
  const double cell_area = c.result->grid.dx * c.result->grid.dy;
  double largest = kNaN, flooded = 0.0;
  for (const double d : map) {
    if (std::isnan(d)) continue;
    largest = std::isnan(largest) ? d : std::max(largest, d);
    if (d > e.thresholds_m.front()) flooded += cell_area;
  }
  c.max_depth_m = largest;
  c.flooded_area_m2 = flooded;
  return c;
}

void write_members_table(const ensemble::Ensemble& e, const std::vector<ensemble::Member>& members,
                         const std::vector<CollectedMember>& collected) {
  std::vector<std::string> columns{"member", "folder"};
  for (const auto& k : e.knobs) columns.push_back(text_field(k.name));
  for (const char* c :
       {"status", "exit_status", "wall_s", "peak_memory_mib", "max_depth_m", "flooded_area_m2",
        "final_volume_error", "host", "job", "resumed", "message"}) {
    columns.emplace_back(c);
  }
  std::string text = csv_line(columns);
  for (std::size_t i = 0; i < members.size(); ++i) {
    const CollectedMember& c = collected[i];
    std::vector<std::string> fields{std::to_string(i),
                                    ensemble::member_folder_name(i, members.size())};
    for (const auto& v : members[i].values) fields.push_back(text_field(v));
    fields.push_back(c.status);
    fields.push_back(c.record ? std::to_string(c.record->exit_status) : std::string());
    fields.push_back(number_text(c.record ? c.record->wall_s : kNaN));
    fields.push_back(number_text(c.record ? c.record->peak_memory_mib : kNaN));
    fields.push_back(number_text(c.max_depth_m));
    fields.push_back(number_text(c.flooded_area_m2));
    fields.push_back(number_text(c.result ? c.result->final_volume_error : kNaN));
    fields.push_back(text_field(c.record ? c.record->host : ""));
    fields.push_back(text_field(c.record ? c.record->job : ""));
    fields.push_back(c.record && c.record->resumed ? "yes" : "");
    fields.push_back(text_field(c.message));
    text += csv_line(fields);
  }
  write_whole_file(e.folder / kMembersTable, text);
}

std::string index_list(const std::vector<std::size_t>& indices) {
  std::string text;
  constexpr std::size_t kShown = 20;
  for (std::size_t k = 0; k < std::min(indices.size(), kShown); ++k) {
    text += (k > 0 ? ", " : "") + std::to_string(indices[k]);
  }
  if (indices.size() > kShown) text += fmt::format(" and {} more", indices.size() - kShown);
  return text;
}

// The products of an earlier collection, which no longer match the members when this one
// makes none.
void remove_stale_products(const ensemble::Ensemble& e) {
  std::error_code ec;
  std::size_t removed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(e.folder, ec)) {
    const std::string name = entry.path().filename().string();
    const bool product = name == std::string(kProductsStem) + ".nc" ||
                         (name.rfind(std::string(kProductsStem) + "_", 0) == 0 &&
                          entry.path().extension() == ".tif");
    if (product && std::filesystem::remove(entry.path(), ec)) ++removed;
  }
  if (removed > 0) {
    spdlog::info(
        "removed the {} product files of an earlier collection: they no longer match "
        "the members",
        removed);
  }
}

// The members table, and the products when every member finished (or, with `partial`, any
// did). Each member's map is added as it is read, so memory holds a few maps whatever the
// number of members. Returns the members that did not finish.
std::vector<std::size_t> collect(const ensemble::Ensemble& e,
                                 const std::vector<ensemble::Member>& members, bool partial) {
  std::vector<CollectedMember> collected;
  std::vector<std::size_t> used, unfinished;
  std::optional<io::Grid> grid;
  std::optional<ensemble::ProductsAccumulator> accumulator;
  for (std::size_t i = 0; i < members.size(); ++i) {
    collected.push_back(collect_member(e, i));
    CollectedMember& c = collected.back();
    if (c.status == "ok" && grid && !io::same_grid(c.result->grid, *grid)) {
      c.status = "failed";
      c.message = fmt::format(
          "its grid differs from member {}'s: the maps of members must cover the same cells "
          "(a knob that moves the domain or the output grid makes members that cannot combine)",
          used.front());
    }
    if (c.status == "ok") {
      if (!grid) {
        grid = c.result->grid;
        accumulator.emplace(grid->nx * grid->ny, e.thresholds_m);
      }
      accumulator->add(c.result->max_depth);
      used.push_back(i);
    } else {
      unfinished.push_back(i);
    }
    if (c.result) c.result->max_depth = {};
  }
  write_members_table(e, members, collected);
  spdlog::info("wrote {}", (e.folder / kMembersTable).string());
  if (used.empty() || (!unfinished.empty() && !partial)) {
    remove_stale_products(e);
    return unfinished;
  }

  const ensemble::Products products = accumulator->finish();
  io::EnsembleSource source{
      fmt::format("{}: an ensemble of the scene {}", e.file.filename().string(),
                  e.base_scene.filename() == "scenario.json"
                      ? e.base_scene.parent_path().filename().string()
                      : e.base_scene.stem().string()),
      e.file.filename().string(), std::string("swe-mps ") + SWEMPS_VERSION, members.size(), used};
  const std::filesystem::path netcdf = e.folder / (std::string(kProductsStem) + ".nc");
  try {
    io::write_ensemble_netcdf(netcdf, *grid, products, source);
    const auto rasters = io::write_ensemble_rasters(e.folder / kProductsStem, *grid, products,
                                                    source, io::TiffLayout::cloud_optimised);
    spdlog::info("wrote {} and {} GeoTIFFs ({}_*.tif) from {} of {} members", netcdf.string(),
                 rasters.size(), (e.folder / kProductsStem).string(), used.size(), members.size());
  } catch (const std::runtime_error& error) {
    throw OutputError(error.what());
  }
  return unfinished;
}

// Ends the command: 0 when every member finished, else exit_members_failed naming them.
// `again` is the command that runs the ensemble again.
void report(const std::vector<std::size_t>& unfinished, std::size_t count, const std::string& again,
            bool partial, const std::filesystem::path& table) {
  if (unfinished.empty()) return;
  throw CommandFailed(
      exit_members_failed,
      fmt::format("{} of {} members did not finish (member{} {}); {} says why; `{} "
                  "--failed-only` runs them again{}",
                  unfinished.size(), count, unfinished.size() == 1 ? "" : "s",
                  index_list(unfinished), table.string(), again,
                  partial ? "" : ", and --partial makes the products without them"));
}

// ---------------------------------------------------------------------------------------------
// The local backend

// The member's process, `swe-mps ensemble FILE --member N`; what it says on standard error
// comes through the pipe, for a member that leaves no record.
Child start_member(const ensemble::Ensemble& e, std::size_t index, int threads) {
  return fork_child(index, [&](int write_fd) {
    // Its own process group: a Ctrl-C at the terminal reaches this process alone, which
    // passes it on to every member's group (run_locally) rather than each racing to stop.
    ::setpgid(0, 0);
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, STDOUT_FILENO);
    ::dup2(write_fd, STDERR_FILENO);
    const std::string exe = own_executable().string(), member = std::to_string(index),
                      thread_count = std::to_string(threads), folder = e.folder.string();
    std::vector<const char*> argv{exe.c_str(),          "ensemble",     e.file.c_str(),
                                  "--member",           member.c_str(), "--threads",
                                  thread_count.c_str(), "--quiet",      "--output",
                                  folder.c_str(),       nullptr};
    ::execv(exe.c_str(), const_cast<char* const*>(argv.data()));
    std::fprintf(stderr, "swe-mps: cannot start member %zu: %s\n", index, std::strerror(errno));
    ::_exit(exit_internal);
  });
}

std::string finished_line(const ensemble::Ensemble& e, const ensemble::Member& m, std::size_t count,
                          const std::optional<MemberRecord>& record, int wait_status,
                          const std::string& said) {
  std::string line = fmt::format("member {}/{} ({}): ", m.index + 1, count, describe(e, m));
  if (!record) {
    std::string why = said;
    if (const auto nl = why.find_last_not_of("\n "); nl != std::string::npos) why.resize(nl + 1);
    if (const auto last = why.rfind('\n'); last != std::string::npos) why = why.substr(last + 1);
    return line + "no record, its process " + wait_status_text(wait_status) +
           (why.empty() ? "" : ": " + why);
  }
  line += record->status +
          fmt::format(", {:.3g} s, {:.0f} MiB", record->wall_s, record->peak_memory_mib);
  constexpr std::size_t kShown = 160;
  if (record->status != "ok") {
    line += ": " + (record->message.size() > kShown ? record->message.substr(0, kShown) + "..."
                                                    : record->message);
  }
  return line;
}

// Runs the members, `jobs` at once. SIGINT or SIGTERM stops them well: each member's process
// group gets SIGTERM, its run writes what it has and stops, and its member records that;
// no member starts after the signal. Returns the signal (0 when none came).
int run_locally(const ensemble::Ensemble& e, const std::vector<ensemble::Member>& members,
                const std::vector<std::size_t>& to_run, int jobs, int threads, bool show) {
  const StopSignals signals;
  SweepProgress progress(std::vector<double>(to_run.size(), 1.0), show);
  std::size_t going_count = 0;
  bool forwarded = false;
  PoolCalls calls;
  calls.start = [&](std::size_t run) {
    ++going_count;
    return start_member(e, to_run[run], threads);
  };
  calls.between = [&](std::vector<Child>& going) {
    if (signals.received() != 0 && !forwarded) {
      for (const Child& c : going) ::kill(-c.pid, SIGTERM);
      forwarded = true;
    }
    progress.tick(going.size());
    return !forwarded;
  };
  calls.ended = [&](const Child& child, int status, const rusage&, const std::string& said) {
    --going_count;
    const auto record = read_member_record(member_folder(e, child.task));
    const auto run = static_cast<std::size_t>(std::find(to_run.begin(), to_run.end(), child.task) -
                                              to_run.begin());
    progress.finished(run,
                      finished_line(e, members[child.task], members.size(), record, status, said),
                      going_count);
  };
  std::vector<std::size_t> order(to_run.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  run_pool(order, jobs, calls);
  progress.finish();
  return signals.received();
}

std::vector<std::size_t> members_to_run(const ensemble::Ensemble& e, std::size_t count,
                                        bool failed_only) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < count; ++i) {
    if (!failed_only || !finished(read_member_record(member_folder(e, i)))) out.push_back(i);
  }
  return out;
}

}  // namespace

void ensemble(const Options& options, const std::string& /*command_line*/) {
  ensemble::Ensemble e = scenario::load_ensemble(options.scenario);
  if (options.output) e.folder = output_option(*options.output);
  const int threads = options.threads > 0 ? options.threads : e.threads_per_member;
  // The command that runs this ensemble again, for messages.
  const std::string again = "swe-mps ensemble " + options.scenario.string() +
                            (options.output ? " -o " + options.output->string() : "");

  const std::size_t count = ensemble::member_count(e);
  if (options.member) {
    if (*options.member >= count) {
      throw UsageError(fmt::format("--member {}: the ensemble has {} members, 0 to {}",
                                   *options.member, count, count - 1));
    }
    // A scheduler's task runs one member: the others are not made.
    const ensemble::Member m = ensemble::member(e, *options.member);
    spdlog::info("member {} of {} ({}) in {}", m.index, count, describe(e, m),
                 member_folder(e, m.index).string());
    const MemberRecord r = run_member(e, m, threads);
    if (r.status != "ok") {
      throw CommandFailed(r.exit_status,
                          fmt::format("member {}: {}: {}", m.index, r.status, r.message));
    }
    spdlog::info("member {}: ok, {:.3g} s", m.index, r.wall_s);
    return;
  }
  const std::vector<ensemble::Member> members = ensemble::members(e);

  if (options.collect) {
    spdlog::info("ensemble '{}': collecting {} members from {}", options.scenario.string(),
                 members.size(), e.folder.string());
    report(collect(e, members, options.partial), members.size(), again, options.partial,
           e.folder / kMembersTable);
    return;
  }

  // Every member's scene is written, and so read as its run will read it, before any runs.
  for (const auto& m : members) write_member_scene(e, m);
  if (options.plan) {
    collect(e, members, false);
    spdlog::info("ensemble '{}': {} members planned in {}", options.scenario.string(),
                 members.size(), e.folder.string());
    return;
  }
  const std::vector<std::size_t> to_run = members_to_run(e, members.size(), options.failed_only);

  if (options.submit) {
    SlurmRequest request{e, to_run, threads, options};
    submit_to_slurm(request);
    return;
  }

  const int jobs = std::clamp(
      options.jobs > 0 ? options.jobs : e.jobs.value_or(std::max(1, usable_cores() / threads)), 1,
      static_cast<int>(std::max<std::size_t>(1, to_run.size())));
  spdlog::info("ensemble '{}': {} of {} members to run here, {} at once, {} thread{} each",
               options.scenario.string(), to_run.size(), members.size(), jobs, threads,
               threads == 1 ? "" : "s");
  const auto start = Clock::now();
  const int signal =
      run_locally(e, members, to_run, jobs, threads, options.verbosity != Verbosity::quiet);
  if (signal != 0) {
    const auto unfinished = collect(e, members, false);
    throw RunStopped(signal,
                     fmt::format("the ensemble stopped on {}: {} of {} members have not "
                                 "finished; `{} --failed-only` runs them",
                                 signal_name(signal), unfinished.size(), members.size(), again));
  }
  spdlog::info("ran {} members in {:.1f} s", to_run.size(), seconds_since(start));
  report(collect(e, members, options.partial), members.size(), again, options.partial,
         e.folder / kMembersTable);
}

}  // namespace swemps::cli
