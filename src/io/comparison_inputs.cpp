#include "swemps/io/comparison_inputs.hpp"

#include <cctype>
#include <charconv>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "csv_text.hpp"
#include "result_reader.hpp"

namespace swemps::io {

using namespace netcdf;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

GaugeSeries read_gauge_series(const std::filesystem::path& result) {
  const ResultReader in(result);
  GaugeSeries s;
  if (!in.has("gauge_name")) return s;
  s.names = in.strings("gauge_name");
  s.time_s = in.values("series_time");
  const std::vector<double> depth = in.values("gauge_depth");
  const std::size_t n = s.names.size();
  if (depth.size() != s.time_s.size() * n) {
    throw std::runtime_error("the result " + quoted(result) + " has " +
                             std::to_string(depth.size()) + " values of gauge_depth for " +
                             std::to_string(s.time_s.size()) + " times and " + std::to_string(n) +
                             " gauges");
  }
  s.depth_m.assign(n, std::vector<double>(s.time_s.size()));
  for (std::size_t t = 0; t < s.time_s.size(); ++t) {
    for (std::size_t g = 0; g < n; ++g) s.depth_m[g][t] = depth[t * n + g];
  }
  return s;
}

const std::vector<double>& NumericTable::column(const std::string& name) const {
  for (std::size_t k = 0; k < columns.size(); ++k) {
    if (columns[k] == name) return values[k];
  }
  std::string names;
  for (const auto& c : columns) names += (names.empty() ? "" : ", ") + c;
  throw std::runtime_error(quoted(file) + ": no column '" + name + "' (it has " + names + ")");
}

NumericTable read_numeric_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(quoted(path) + ": cannot be read");
  NumericTable table;
  table.file = path;
  const auto fail = [&](std::size_t line, const std::string& problem) {
    throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": " + problem);
  };
  std::string text;
  std::size_t line = 0;
  bool header = true;
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const std::string_view content = csv::trim(text);
    if (content.empty() || content.front() == '#') continue;
    const auto fields = csv::split_commas(content);
    if (header) {
      for (const auto f : fields) {
        if (f.empty()) fail(line, "an empty column name in the header");
        table.columns.emplace_back(f);
      }
      table.values.resize(fields.size());
      header = false;
      continue;
    }
    if (fields.size() != table.columns.size()) {
      fail(line, std::to_string(fields.size()) + " fields, where the header names " +
                     std::to_string(table.columns.size()));
    }
    for (std::size_t k = 0; k < fields.size(); ++k) {
      double v = kNaN;
      if (!fields[k].empty()) {
        const auto [end, ec] =
            std::from_chars(fields[k].data(), fields[k].data() + fields[k].size(), v);
        if (ec != std::errc() || end != fields[k].data() + fields[k].size()) {
          std::string problem = "'";
          problem += fields[k];
          problem += "' in column " + table.columns[k] + " is not a number";
          fail(line, problem);
        }
      }
      table.values[k].push_back(v);
    }
  }
  if (header) throw std::runtime_error(quoted(path) + ": no header (the file is empty)");
  return table;
}

}  // namespace swemps::io
