#pragma once
// Command-line options of the swe-mps executable.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace swemps::cli {

enum class Verbosity { quiet, normal, verbose };

struct Options {
  // "run", "compare", "study", "ensemble", "check", "export", or "help" / "version"
  std::string command;
  std::filesystem::path scenario;  // the scene; study: the study file; export: the result
  // -o: run writes here instead of the scene's output path; compare takes it as the stem of
  // its files; study writes its table here.
  std::optional<std::filesystem::path> output;
  int threads = 0;  // 0: OpenMP's default; study: threads per run, 0: cores / jobs
  int jobs = 0;     // study: runs at once; 0: the study file's, or one per core
  Verbosity verbosity = Verbosity::normal;
  // run, shallow water: continue the run that wrote this checkpoint (--restart)
  std::optional<std::filesystem::path> restart;
  // run, shallow water: write a checkpoint every this many output times; 0: only when the
  // run stops early (a signal, a breakdown)
  int checkpoint_every = 0;
  // export: the maps to write (empty: all) and the GeoTIFF layout ("cog" or "geotiff"; empty:
  // "cog")
  std::vector<std::string> maps;
  std::string format;
  // ensemble: what to do (docs/ensembles.md). None of these: run every member on this machine
  // and collect.
  std::optional<std::size_t> member;  // --member N: run member N alone
  bool plan = false;                  // --plan: write the members' scenes, run nothing
  bool collect = false;               // --collect: the products of the members that ran
  bool submit = false;                // --submit: run the members as a Slurm job array
  bool failed_only = false;           // --failed-only: only members without a finished run
  bool partial = false;               // --partial: products from the finished members alone
  // --submit: sbatch settings over the ensemble file's
  std::string partition, account, time_limit, memory;
  std::optional<int> max_running;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Options parse_options(const std::vector<std::string>& args);  // args without argv[0]
std::string usage_text();

}  // namespace swemps::cli
