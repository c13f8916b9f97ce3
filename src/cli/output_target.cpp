#include "swemps/cli/output_target.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "swemps/cli/run_command.hpp"
#include "swemps/scenario/scenario.hpp"

namespace swemps::cli {

namespace {

std::string quoted(const std::filesystem::path& p) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "'" + string + "'".
  std::string out = "'";
  out += p.string();
  out += '\'';
  return out;
}

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& problem) {
  // File names may hold line breaks; the message stays one line.
  throw OutputError(scenario::printable_line(quoted(file) + ": " + problem));
}

// The nearest ancestor of `folder` that exists (the root at worst), to say whether a missing
// folder is missing or stands under a file.
std::filesystem::path existing_ancestor(std::filesystem::path folder) {
  std::error_code ec;
  while (!std::filesystem::exists(folder, ec) && folder.has_relative_path()) {
    folder = folder.parent_path();
  }
  return folder;
}

}  // namespace

void check_output_target(const std::filesystem::path& file) {
  if (file.empty() || !file.has_filename()) {
    refuse(file, "names no file (give a file name such as out.nc)");
  }
  const std::filesystem::path folder = file.parent_path();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    refuse(file, "is a folder; give a file name inside it, such as " + quoted(file / "out.nc"));
  }
  if (!std::filesystem::is_directory(folder, ec)) {
    const std::filesystem::path ancestor = existing_ancestor(folder);
    if (std::filesystem::exists(ancestor, ec) && !std::filesystem::is_directory(ancestor, ec)) {
      refuse(file, quoted(ancestor) + " is a file, not a folder");
    }
    refuse(file, "the folder " + quoted(folder) +
                     " does not exist (swe-mps does not create folders; create it first)");
  }
  std::filesystem::path partial = file;
  partial += ".partial";
  if (std::filesystem::is_directory(partial, ec)) {
    refuse(file, "the folder " + quoted(partial) + " is in the way of the file written first");
  }
  const bool existed = std::filesystem::exists(partial, ec);
  errno = 0;
  const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    refuse(file, "cannot create files in the folder " + quoted(folder) + ": " +
                     (err != 0 ? std::strerror(err) : "unknown reason"));
  }
  ::close(fd);
  if (!existed) std::filesystem::remove(partial, ec);
}

std::filesystem::path output_option(const std::filesystem::path& given) {
  return given.empty() ? given : std::filesystem::absolute(given).lexically_normal();
}

void write_whole_file(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::path partial = file;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw OutputError("cannot write " + quoted(partial));
  }
  std::error_code ec;
  std::filesystem::rename(partial, file, ec);
  if (ec) {
    throw OutputError("cannot rename " + quoted(partial) + " to " + quoted(file) + ": " +
                      ec.message());
  }
}

}  // namespace swemps::cli
