#pragma once
// What a comparison with a reference reads besides rasters: the depth series at a run's gauges
// (from its netCDF result) and a reference's series as a plain CSV table of numbers.

#include <filesystem>
#include <string>
#include <vector>

namespace swemps::io {

// The depth at each gauge of a run, at every series time; NaN where the gauge was dry.
struct GaugeSeries {
  std::vector<std::string> names;
  std::vector<double> time_s;
  std::vector<std::vector<double>> depth_m;  // one series per gauge, in the order of `names`
};

// Reads the gauge series of a run's netCDF result; no names when it has no gauges. Throws
// std::runtime_error naming the file when it cannot be read or is not a swe-mps result.
GaugeSeries read_gauge_series(const std::filesystem::path& result);

// A CSV table of numbers with a header row. Blank lines and lines starting with '#' are
// skipped; fields may have spaces around them; an empty field is NaN (a dry gauge, in the
// tables swe-mps writes); anything else must be a number. Every row has the header's number
// of fields.
struct NumericTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> values;  // one vector per column, a value per row

  // The values of the column named `name`; throws std::runtime_error naming the file and the
  // columns it has when there is none.
  const std::vector<double>& column(const std::string& name) const;
  std::filesystem::path file;
};

// Throws std::runtime_error, one line "FILE:LINE: problem" (or "FILE: problem").
NumericTable read_numeric_csv(const std::filesystem::path& path);

}  // namespace swemps::io
