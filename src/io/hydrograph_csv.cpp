#include "swemps/io/hydrograph_csv.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "csv_text.hpp"

namespace swemps::io {

using csv::split_commas;
using csv::trim;

namespace {

enum class Column { time, discharge };

std::string lower_without_spaces(std::string_view s) {
  std::string out;
  for (const char c : s) {
    if (!std::isspace(static_cast<unsigned char>(c))) {
      out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
    }
  }
  return out;
}

// Which column a header name names, or nullopt with `why` set.
std::optional<Column> column_named(std::string_view field, std::string& why) {
  std::string name = lower_without_spaces(field);
  std::string unit;
  bool has_unit = false;
  for (const auto& [open, close] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    const std::size_t at = name.find(open);
    if (at != std::string::npos && !name.empty() && name.back() == close) {
      unit = name.substr(at + 1, name.size() - at - 2);
      name.resize(at);
      has_unit = true;
      break;
    }
  }
  if (!has_unit) {
    const std::size_t at = name.find('_');
    if (at != std::string::npos) {
      unit = name.substr(at + 1);
      name.resize(at);
      has_unit = true;
    }
  }
  const std::string quoted = "column '" + std::string(field) + "'";
  if (name == "time" || name == "t") {
    if (!has_unit || unit == "s") return Column::time;
    why = quoted + ": times must be in s, not '" + unit + "'";
    return std::nullopt;
  }
  if (name == "discharge" || name == "q") {
    if (!has_unit || unit == "m3/s" || unit == "m^3/s" || unit == "m3_s" || unit == "m3s-1") {
      return Column::discharge;
    }
    why = quoted + ": discharges must be in m3/s, not '" + unit + "'";
    return std::nullopt;
  }
  why = quoted + " is neither time (time, t) nor discharge (discharge, Q)";
  return std::nullopt;
}

// A whole field as a finite number, or nullopt.
std::optional<double> number(std::string_view field) {
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);  // from_chars refuses '+'
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (field.empty() || error != std::errc() || end != field.data() + field.size() ||
      !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

[[noreturn]] void fail(const std::string& file, std::size_t line_number,
                       const std::string& problem) {
  throw std::runtime_error(file + ":" + std::to_string(line_number) + ": " + problem);
}

}  // namespace

std::vector<std::array<double, 2>> read_hydrograph_csv(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw std::runtime_error(file + ": cannot open the hydrograph file");

  std::vector<std::array<double, 2>> points;
  std::size_t time_column = 0;  // index of the time field; the discharge is the other one
  bool have_header = false;
  std::string raw;
  for (std::size_t line_number = 1; std::getline(in, raw); ++line_number) {
    const std::string_view line = trim(raw);  // also drops a Windows '\r'
    if (line.empty() || line.front() == '#') continue;
    const auto fields = split_commas(line);
    if (!have_header) {
      if (fields.size() != 2) {
        fail(file, line_number,
             "the header must name two columns (time and discharge), found " +
                 std::to_string(fields.size()));
      }
      if (number(fields[0]) && number(fields[1])) {
        fail(file, line_number,
             "the first line holds numbers, not a header naming the columns (e.g. "
             "'time_s,discharge_m3_s')");
      }
      std::string why;
      const auto first = column_named(fields[0], why);
      if (!first) fail(file, line_number, why);
      const auto second = column_named(fields[1], why);
      if (!second) fail(file, line_number, why);
      if (*first == *second) fail(file, line_number, "the header names the same column twice");
      time_column = *first == Column::time ? 0 : 1;
      have_header = true;
      continue;
    }
    if (fields.size() != 2) {
      fail(file, line_number, "expected 2 columns, found " + std::to_string(fields.size()));
    }
    const auto t = number(fields[time_column]);
    const auto q = number(fields[1 - time_column]);
    if (!t)
      fail(file, line_number, "time '" + std::string(fields[time_column]) + "' is not a number");
    if (!q) {
      fail(file, line_number,
           "discharge '" + std::string(fields[1 - time_column]) + "' is not a number");
    }
    if (!points.empty() && !(*t > points.back()[0])) {
      std::ostringstream msg;
      msg << "time " << *t << " s is not after the previous time " << points.back()[0] << " s";
      fail(file, line_number, msg.str());
    }
    if (*q < 0.0) {
      std::ostringstream msg;
      msg << "discharge " << *q << " m3/s is negative";
      fail(file, line_number, msg.str());
    }
    points.push_back({*t, *q});
  }
  if (!have_header) {
    throw std::runtime_error(file + ": no header line (expected e.g. 'time_s,discharge_m3_s')");
  }
  if (points.empty()) throw std::runtime_error(file + ": no data lines after the header");
  return points;
}

}  // namespace swemps::io
