#include "swemps/cli/ensemble_member.hpp"

#include <fcntl.h>
#include <spdlog/fmt/fmt.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <thread>
#include <vector>

#include "swemps/cli/child_processes.hpp"
#include "swemps/cli/output_target.hpp"
#include "swemps/cli/run_command.hpp"
#include "swemps/cli/timing.hpp"
#include "swemps/scenario/ensemble_file.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::cli {

namespace {

constexpr const char* kRecord = "record.txt";
constexpr const char* kRunOutput = "run.out";

std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

std::string encode(const MemberRecord& r) {
  return fmt::format(
      "status {}\nexit_status {}\nwall_s {:.17g}\npeak_memory_mib {:.17g}\nhost {}\njob {}\n"
      "resumed {}\nmessage {}\n",
      r.status, r.exit_status, r.wall_s, r.peak_memory_mib, one_line(r.host), one_line(r.job),
      r.resumed ? 1 : 0, one_line(r.message));
}

// The last line of the run's output that says something: the reason a failed run gives.
std::string last_line(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line)) {
    // A progress bar redraws with carriage returns; its last state is what was shown.
    if (const auto cr = line.rfind('\r'); cr != std::string::npos) line = line.substr(cr + 1);
    if (line.find_first_not_of(" \t") != std::string::npos) last = line;
  }
  constexpr std::size_t kKept = 400;
  return last.size() > kKept ? last.substr(0, kKept) + "..." : last;
}

std::string status_of(int wait_status, bool timed_out) {
  if (timed_out) return "timeout";
  if (WIFSIGNALED(wait_status)) return "killed";
  switch (WEXITSTATUS(wait_status)) {
    case exit_ok: return "ok";
    case exit_input: return "input";
    case exit_breakdown: return "breakdown";
    case exit_output: return "output";
    default: return WEXITSTATUS(wait_status) > exit_signal ? "stopped" : "failed";
  }
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return {};
  return name;
}

// The Slurm array task this runs as, "12345_3"; a plain Slurm job "12345"; empty elsewhere.
std::string scheduler_job() {
  const char* array_job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* array_task = std::getenv("SLURM_ARRAY_TASK_ID");
  if (array_job && array_task) return std::string(array_job) + "_" + array_task;
  const char* job = std::getenv("SLURM_JOB_ID");
  return job ? job : "";
}

// SIGINT and SIGTERM interrupt the wait, and nothing else: the run gets them too (same process
// group, or the scheduler signals every process of the task) and stops as a run does.
volatile std::sig_atomic_t g_signalled = 0;
void note_signal(int) { g_signalled = 1; }

[[noreturn]] void exec_run(const std::filesystem::path& scene, const std::filesystem::path& out,
                           const std::vector<std::string>& options, pid_t parent) {
  // A member whose wrapper is gone (killed) stops too, as a run stops on SIGTERM.
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != parent) ::_exit(exit_signal + SIGTERM);
  const int fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd >= 0) {
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
  }
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
  const std::string exe = own_executable().string();
  std::vector<const char*> argv{exe.c_str(), "run", scene.c_str()};
  for (const auto& option : options) argv.push_back(option.c_str());
  argv.push_back(nullptr);
  ::execv(exe.c_str(), const_cast<char* const*>(argv.data()));
  std::fprintf(stderr, "swe-mps: cannot start the member's run: %s\n", std::strerror(errno));
  ::_exit(exit_internal);
}

}  // namespace

std::filesystem::path member_folder(const ensemble::Ensemble& ensemble, std::size_t index) {
  return ensemble.folder / ensemble::member_folder_name(index, ensemble::member_count(ensemble));
}

std::optional<MemberRecord> read_member_record(const std::filesystem::path& folder) {
  std::ifstream in(folder / kRecord);
  if (!in) return std::nullopt;
  MemberRecord r;
  bool has_status = false;
  std::string line;
  while (std::getline(in, line)) {
    const auto space = line.find(' ');
    const std::string key = line.substr(0, space);
    const std::string value = space == std::string::npos ? "" : line.substr(space + 1);
    if (key == "status") {
      r.status = value;
      has_status = !value.empty();
    } else if (key == "exit_status") {
      r.exit_status = std::atoi(value.c_str());
    } else if (key == "wall_s") {
      r.wall_s = std::strtod(value.c_str(), nullptr);
    } else if (key == "peak_memory_mib") {
      r.peak_memory_mib = std::strtod(value.c_str(), nullptr);
    } else if (key == "host") {
      r.host = value;
    } else if (key == "job") {
      r.job = value;
    } else if (key == "resumed") {
      r.resumed = value == "1";
    } else if (key == "message") {
      r.message = value;
    }
  }
  if (!has_status) return std::nullopt;
  return r;
}

std::filesystem::path write_member_scene(const ensemble::Ensemble& ensemble,
                                         const ensemble::Member& member) {
  const std::filesystem::path folder = member_folder(ensemble, member.index);
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) {
    throw OutputError("cannot make the member's folder '" + folder.string() + "': " + ec.message());
  }
  const std::string text = scenario::member_scene(ensemble, member, folder);
  // Read as the run will read it, so that a value the scene cannot take is reported now, for
  // every member, rather than by a member's run on a cluster node hours later.
  try {
    (void)scenario::parse(text, folder, folder.filename().string());
  } catch (const scenario::ScenarioError& e) {
    throw scenario::ScenarioError(e.json_path(),
                                  e.found() + " (in member " + std::to_string(member.index) + ", " +
                                      (folder / "scenario.json").string() + ")",
                                  e.expected(), e.document());
  }
  const std::filesystem::path scene = folder / "scenario.json";
  write_whole_file(scene, text);
  return scene;
}

// The text of a file; empty when there is none.
std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

MemberRecord run_member(const ensemble::Ensemble& ensemble, const ensemble::Member& member,
                        int threads) {
  const std::filesystem::path folder = member_folder(ensemble, member.index);
  const std::string scene_before = file_text(folder / "scenario.json");
  const std::filesystem::path scene = write_member_scene(ensemble, member);
  const std::filesystem::path result = folder / scenario::kMemberResult;
  std::filesystem::path checkpoint = result, partial = result;
  checkpoint.replace_extension(".checkpoint");  // where a run of this scene writes them
  partial += ".partial";
  const auto earlier = read_member_record(folder);
  const bool resume = (!earlier || earlier->status != "ok") && file_text(scene) == scene_before &&
                      std::filesystem::exists(checkpoint) && std::filesystem::exists(partial);
  // What an earlier run of this member left would otherwise pass for this run's.
  for (const auto& stale : {folder / kRecord, result}) {
    std::error_code ignored;
    std::filesystem::remove(stale, ignored);
  }
  if (!resume) {
    for (const auto& stale : {checkpoint, partial}) {
      std::error_code ignored;
      std::filesystem::remove(stale, ignored);
    }
  }
  std::vector<std::string> options{"--threads", std::to_string(threads)};
  if (ensemble.checkpoint_every) {
    options.insert(options.end(),
                   {"--checkpoint-every", std::to_string(*ensemble.checkpoint_every)});
  }
  if (resume) options.insert(options.end(), {"--restart", checkpoint.string()});

  struct sigaction action {};
  action.sa_handler = note_signal;  // no SA_RESTART: the wait below sees EINTR and goes on
  sigemptyset(&action.sa_mask);
  struct sigaction old_int {
  }, old_term{};
  ::sigaction(SIGINT, &action, &old_int);
  ::sigaction(SIGTERM, &action, &old_term);

  MemberRecord r;
  r.resumed = resume;
  r.host = host_name();
  r.job = scheduler_job();
  std::fflush(stdout);
  std::fflush(stderr);
  const auto start = Clock::now();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    r.message = std::string("cannot start the member's run: fork: ") + std::strerror(errno);
  }
  if (pid == 0) exec_run(scene, folder / kRunOutput, options, parent);

  if (pid > 0) {
    int status = 0;
    rusage usage{};
    bool timed_out = false, waited = false;
    for (;;) {
      const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
      if (done == pid) {
        waited = true;
        break;
      }
      if (done < 0 && errno != EINTR) {
        r.message = std::string("waiting for the member's run: ") + std::strerror(errno);
        break;
      }
      if (!timed_out && ensemble.run_time_limit_s &&
          seconds_since(start) > *ensemble.run_time_limit_s) {
        ::kill(pid, SIGKILL);
        timed_out = true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    r.wall_s = seconds_since(start);
    if (!waited) {
      ::kill(pid, SIGKILL);
      ::sigaction(SIGINT, &old_int, nullptr);
      ::sigaction(SIGTERM, &old_term, nullptr);
      write_whole_file(folder / kRecord, encode(r));
      return r;
    }
    r.peak_memory_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
    r.status = status_of(status, timed_out);
    r.exit_status = WIFSIGNALED(status) ? exit_signal + WTERMSIG(status) : WEXITSTATUS(status);
    if (timed_out) {
      r.message = fmt::format("stopped after the ensemble's run_time_limit of {:g} s",
                              *ensemble.run_time_limit_s);
    } else if (r.status != "ok") {
      const std::string said = last_line(folder / kRunOutput);
      r.message = "the run " + wait_status_text(status) + (said.empty() ? "" : ": " + said);
    }
  }
  ::sigaction(SIGINT, &old_int, nullptr);
  ::sigaction(SIGTERM, &old_term, nullptr);
  write_whole_file(folder / kRecord, encode(r));
  return r;
}

}  // namespace swemps::cli
