#include "swemps/cli/slurm_backend.hpp"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>

#include "swemps/cli/child_processes.hpp"
#include "swemps/cli/run_command.hpp"

namespace swemps::cli {

namespace {

// A word for a shell script, in single quotes.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The sbatch settings of the ensemble file, with the command line's over them.
ensemble::SlurmSettings settings(const SlurmRequest& r) {
  ensemble::SlurmSettings s = r.ensemble.slurm;
  if (!r.options.partition.empty()) s.partition = r.options.partition;
  if (!r.options.account.empty()) s.account = r.options.account;
  if (!r.options.time_limit.empty()) s.time_limit = r.options.time_limit;
  if (!r.options.memory.empty()) s.memory = r.options.memory;
  if (r.options.max_running) s.max_running = r.options.max_running;
  return s;
}

// The "#SBATCH" lines both scripts share.
std::string common_lines(const ensemble::SlurmSettings& s) {
  std::string text;
  const std::pair<const char*, const std::string*> options[] = {
      {"partition", &s.partition}, {"account", &s.account}, {"qos", &s.qos}};
  for (const auto& [name, value] : options) {
    if (!value->empty()) text += fmt::format("#SBATCH --{}={}\n", name, *value);
  }
  for (const auto& extra : s.extra) text += "#SBATCH " + extra + "\n";
  return text;
}

void write_script(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::trunc);
  out << text;
  out.flush();
  if (!out) throw OutputError("cannot write '" + file.string() + "'");
  std::filesystem::permissions(file, std::filesystem::perms::owner_exec,
                               std::filesystem::perm_options::add);
}

// Runs sbatch with `args` and returns the job id it printed (--parsable: "id" or
// "id;cluster").
std::string sbatch(const std::vector<std::string>& args, const std::string& what) {
  std::vector<std::string> argv{"sbatch", "--parsable"};
  argv.insert(argv.end(), args.begin(), args.end());
  const ProgramResult r = run_program(argv);
  std::string id = r.out.substr(0, r.out.find_first_of(";\n"));
  if (r.status != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    std::string said = r.err.empty() ? r.out : r.err;
    while (!said.empty() && (said.back() == '\n' || said.back() == ' ')) said.pop_back();
    throw CommandFailed(
        exit_internal,
        fmt::format("cannot submit {}: sbatch {}{}", what,
                    r.status == 127 ? "was not found (is this a Slurm login node?)"
                                    : "exited with status " + std::to_string(r.status),
                    said.empty() ? "" : ": " + said));
  }
  return id;
}

}  // namespace

std::string array_ranges(const std::vector<std::size_t>& indices) {
  std::string text;
  for (std::size_t k = 0; k < indices.size();) {
    std::size_t end = k;
    while (end + 1 < indices.size() && indices[end + 1] == indices[end] + 1) ++end;
    if (!text.empty()) text += ',';
    text += std::to_string(indices[k]);
    if (end > k) text += fmt::format("-{}", indices[end]);
    k = end + 1;
  }
  return text;
}

void submit_to_slurm(const SlurmRequest& r) {
  const ensemble::Ensemble& e = r.ensemble;
  if (r.members.empty()) {
    spdlog::info(
        "every member has finished: nothing to submit; `swe-mps ensemble {} --collect` "
        "makes the products",
        e.file.string());
    return;
  }
  const ensemble::SlurmSettings s = settings(r);
  const std::filesystem::path dir = e.folder / "slurm";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError("cannot make the folder '" + dir.string() + "': " + ec.message());

  const std::string exe = quoted(own_executable().string()), file = quoted(e.file.string()),
                    folder = quoted(e.folder.string()), name = e.file.stem().string();
  std::string member =
      "#!/bin/bash\n# One member of the ensemble per array task (swe-mps ensemble --submit).\n";
  member += fmt::format("#SBATCH --job-name={}\n#SBATCH --cpus-per-task={}\n#SBATCH --ntasks=1\n",
                        name, r.threads);
  member += fmt::format("#SBATCH --output={}\n", (dir / "member-%a.out").string());
  if (!s.time_limit.empty()) member += "#SBATCH --time=" + s.time_limit + "\n";
  if (!s.memory.empty()) member += "#SBATCH --mem=" + s.memory + "\n";
  member += common_lines(s);
  member += fmt::format(
      "exec {} ensemble {} --member \"$SLURM_ARRAY_TASK_ID\" --threads {} --output {}\n", exe, file,
      r.threads, folder);
  std::string collect =
      "#!/bin/bash\n# The ensemble's products, once every member's task has ended.\n";
  collect += fmt::format(
      "#SBATCH --job-name={}-collect\n#SBATCH --cpus-per-task=1\n#SBATCH --ntasks=1\n", name);
  collect += fmt::format("#SBATCH --output={}\n", (dir / "collect-%j.out").string());
  collect += common_lines(s);
  collect += fmt::format("exec {} ensemble {} --collect --output {}\n", exe, file, folder);
  write_script(dir / "member.sbatch", member);
  write_script(dir / "collect.sbatch", collect);

  std::string array = array_ranges(r.members);
  if (s.max_running) array += fmt::format("%{}", *s.max_running);
  const std::string array_job =
      sbatch({"--array=" + array, (dir / "member.sbatch").string()}, "the members' job array");
  // afterany: the collection runs however the members ended, and says which did not finish.
  const std::string collect_job =
      sbatch({"--dependency=afterany:" + array_job, (dir / "collect.sbatch").string()},
             "the collection job");
  std::ofstream log(dir / "submitted.txt", std::ios::app);
  log << fmt::format("array {} members {} collect {}\n", array_job, array, collect_job);
  spdlog::info(
      "submitted {} member{} as job array {} (--array={}) and the collection as job {}, "
      "which starts when they have ended; `squeue -j {},{}` follows them; the products go to {}",
      r.members.size(), r.members.size() == 1 ? "" : "s", array_job, array, collect_job, array_job,
      collect_job, e.folder.string());
}

}  // namespace swemps::cli
