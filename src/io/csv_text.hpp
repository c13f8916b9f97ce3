#pragma once
// Private to the io module: the text of the CSV tables it reads (hydrographs, reference
// series), split into trimmed fields.

#include <cctype>
#include <string_view>
#include <vector>

namespace swemps::io::csv {

// `s` without the white space around it (a Windows '\r' included).
inline std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// The line's comma-separated fields, each trimmed; no quoting.
inline std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

}  // namespace swemps::io::csv
