#include "text_file.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "netcdf_layout.hpp"

namespace swemps::io::text {

void write_then_rename(const std::filesystem::path& file, const std::filesystem::path& partial,
                       std::string_view text) {
  errno = 0;
  std::FILE* out = std::fopen(partial.c_str(), "w");
  if (out == nullptr) {
    throw std::runtime_error("cannot create " + netcdf::quoted(partial) + ": " +
                             (errno != 0 ? std::strerror(errno) : "unknown reason"));
  }
  bool good = std::fwrite(text.data(), 1, text.size(), out) == text.size();
  good = std::fclose(out) == 0 && good;
  std::error_code ec;
  if (!good) {
    std::filesystem::remove(partial, ec);
    throw std::runtime_error("cannot write " + netcdf::quoted(partial));
  }
  std::filesystem::rename(partial, file, ec);
  if (ec) {
    std::filesystem::remove(partial, ec);
    throw std::runtime_error("cannot rename " + netcdf::quoted(partial) + " to " +
                             netcdf::quoted(file));
  }
}

}  // namespace swemps::io::text
