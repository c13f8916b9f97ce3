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

enum class Column { time, value };

// What the second column of a series holds: its names, its units and its sign.
struct ValueColumn {
  std::string_view what;                // "discharge", in messages
  std::vector<std::string_view> names;  // lower case, e.g. "discharge", "q"
  std::string_view named;               // the names as messages list them
  std::vector<std::string_view> units;  // lower case, spaces removed
  std::string_view unit;                // the unit in messages
  std::string_view example_header;      // a header that works
  bool non_negative = false;
};

const ValueColumn kDischarge{"discharge",
                             {"discharge", "q"},
                             "discharge, Q",
                             {"m3/s", "m^3/s", "m3_s", "m3s-1"},
                             "m3/s",
                             "time_s,discharge_m3_s",
                             true};

const ValueColumn kLevel{
    "level", {"level", "eta", "elevation"}, "level, eta, elevation", {"m"}, "m", "time_s,level_m",
    false};

const ValueColumn kRain{"rain rate",
                        {"rain", "rainfall", "rate", "intensity"},
                        "rain, rainfall, rate, intensity",
                        {"mm/h", "mm_h", "mm/hr", "mmh-1", "mmhr-1"},
                        "mm/h",
                        "time_s,rain_mm_h",
                        true};

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
std::optional<Column> column_named(std::string_view field, const ValueColumn& value,
                                   std::string& why) {
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
  if (std::find(value.names.begin(), value.names.end(), name) != value.names.end()) {
    if (!has_unit || std::find(value.units.begin(), value.units.end(), unit) != value.units.end())
      return Column::value;
    why = quoted + ": " + std::string(value.what) + "s must be in " + std::string(value.unit) +
          ", not '" + unit + "'";
    return std::nullopt;
  }
  why = quoted + " is neither time (time, t) nor " + std::string(value.what) + " (" +
        std::string(value.named) + ")";
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

// The (time, value) points of a two-column series file (hydrograph_csv.hpp says what is
// accepted, for any value column).
std::vector<std::array<double, 2>> read_series(const std::filesystem::path& path,
                                               const ValueColumn& value) {
  const std::string file = path.string();
  const std::string what(value.what);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(file + ": cannot open the " + what + " series file");

  std::vector<std::array<double, 2>> points;
  std::size_t time_column = 0;  // index of the time field; the value is the other one
  bool have_header = false;
  std::string raw;
  for (std::size_t line_number = 1; std::getline(in, raw); ++line_number) {
    const std::string_view line = trim(raw);  // also drops a Windows '\r'
    if (line.empty() || line.front() == '#') continue;
    const auto fields = split_commas(line);
    if (!have_header) {
      if (fields.size() != 2) {
        fail(file, line_number,
             "the header must name two columns (time and " + what + "), found " +
                 std::to_string(fields.size()));
      }
      if (number(fields[0]) && number(fields[1])) {
        fail(file, line_number,
             "the first line holds numbers, not a header naming the columns (e.g. '" +
                 std::string(value.example_header) + "')");
      }
      std::string why;
      const auto first = column_named(fields[0], value, why);
      if (!first) fail(file, line_number, why);
      const auto second = column_named(fields[1], value, why);
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
           what + " '" + std::string(fields[1 - time_column]) + "' is not a number");
    }
    if (!points.empty() && !(*t > points.back()[0])) {
      std::ostringstream msg;
      msg << "time " << *t << " s is not after the previous time " << points.back()[0] << " s";
      fail(file, line_number, msg.str());
    }
    if (value.non_negative && *q < 0.0) {
      std::ostringstream msg;
      msg << what << " " << *q << " " << value.unit << " is negative";
      fail(file, line_number, msg.str());
    }
    points.push_back({*t, *q});
  }
  if (!have_header) {
    throw std::runtime_error(file + ": no header line (expected e.g. '" +
                             std::string(value.example_header) + "')");
  }
  if (points.empty()) throw std::runtime_error(file + ": no data lines after the header");
  return points;
}

}  // namespace

std::vector<std::array<double, 2>> read_hydrograph_csv(const std::filesystem::path& path) {
  return read_series(path, kDischarge);
}

std::vector<std::array<double, 2>> read_level_csv(const std::filesystem::path& path) {
  return read_series(path, kLevel);
}

std::vector<std::array<double, 2>> read_rain_csv(const std::filesystem::path& path) {
  return read_series(path, kRain);
}

}  // namespace swemps::io
