#pragma once
// Private to the io module: the text tables the products write (gauge series, gauge arrivals),
// each built whole in memory and written under a temporary name, so that a file with its
// final name is always complete.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace swemps::io::text {

// ",<v>" with 12 significant digits (times and positions exact far below their meaning), or
// "," alone for NaN: an empty cell.
inline void append_cell(std::string& line, double v) {
  line += ',';
  if (std::isnan(v)) return;
  char number[32];
  std::snprintf(number, sizeof number, "%.12g", v);
  line += number;
}

// Writes `text` to `partial`, then renames it to `file`; on failure removes `partial` and
// throws std::runtime_error naming the file.
void write_then_rename(const std::filesystem::path& file, const std::filesystem::path& partial,
                       std::string_view text);

}  // namespace swemps::io::text
