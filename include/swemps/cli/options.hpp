#pragma once
// Command-line options of the swe-mps executable.

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace swemps::cli {

enum class Verbosity { quiet, normal, verbose };

struct Options {
  // "run", "compare", "study", "check", "export", or "help" / "version"
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
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Options parse_options(const std::vector<std::string>& args);  // args without argv[0]
std::string usage_text();

}  // namespace swemps::cli
