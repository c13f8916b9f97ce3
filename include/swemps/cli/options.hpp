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
  std::string command;  // "run", or "help" / "version"
  std::filesystem::path scenario;
  std::optional<std::filesystem::path> output;  // -o overrides the scene's output path
  int threads = 0;                              // 0: OpenMP's default
  Verbosity verbosity = Verbosity::normal;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Options parse_options(const std::vector<std::string>& args);  // args without argv[0]
std::string usage_text();

}  // namespace swemps::cli
