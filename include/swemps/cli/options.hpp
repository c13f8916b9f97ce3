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
  std::string command;  // "run", "compare", or "help" / "version"
  std::filesystem::path scenario;
  // -o: run writes here instead of the scene's output path; compare takes it as the stem of
  // its files.
  std::optional<std::filesystem::path> output;
  int threads = 0;  // 0: OpenMP's default
  Verbosity verbosity = Verbosity::normal;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Options parse_options(const std::vector<std::string>& args);  // args without argv[0]
std::string usage_text();

}  // namespace swemps::cli
