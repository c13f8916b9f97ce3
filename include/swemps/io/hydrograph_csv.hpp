#pragma once
// Hydrographs and level series in: two-column CSV files of times and discharges, or of times
// and water levels.
//
// What is accepted, exactly:
//  - Comma-separated, one point per line. Blank lines and lines whose first non-blank
//    character is '#' are skipped anywhere in the file; fields may have spaces around them;
//    Windows line ends are fine.
//  - The first other line is the header naming the two columns, in either order. A column
//    name is a base name, optionally followed by a unit as `name [unit]`, `name (unit)` or
//    `name_unit`, all case-insensitive:
//      time:      base `time` or `t`;       unit (if any) `s`
//      discharge: base `discharge` or `q`;  unit (if any) `m3/s`, `m^3/s`, `m3_s`, `m3s-1`
//    (spaces inside a unit are ignored). So `time,discharge`, `time_s,discharge_m3_s` and
//    `t [s], Q [m3/s]` all work. Other units are refused, not converted: a time column in
//    hours read as seconds would silently stretch the flood.
//  - Every following line holds exactly two finite numbers (decimal point, optional exponent).
//    Times strictly increase; discharges are >= 0; at least one data line.
//  - A level series is read by the same rules, its second column named `level`, `eta` or
//    `elevation`, with the unit `m` if any (`time_s,level_m`, `t [s], eta [m]`); levels may
//    be negative (a datum above the sea bed's lowest point is common).
//  - A rain series is read by the same rules, its second column named `rain`, `rainfall`,
//    `rate` or `intensity`, with the unit `mm/h` if any (`time_s,rain_mm_h`,
//    `t [s], rain [mm/h]`); rates are >= 0.

#include <array>
#include <filesystem>
#include <vector>

namespace swemps::io {

// Returns the (time s, discharge m^3/s) points in file order, ready for
// boundaries::Hydrograph. Throws std::runtime_error, one line "FILE:LINE: problem" (or
// "FILE: problem" for a missing or empty file).
std::vector<std::array<double, 2>> read_hydrograph_csv(const std::filesystem::path& path);
// The (time s, level m) points of a level series, in file order; errors as above.
std::vector<std::array<double, 2>> read_level_csv(const std::filesystem::path& path);
// The (time s, rate mm/h) points of a rain series, in file order; errors as above.
std::vector<std::array<double, 2>> read_rain_csv(const std::filesystem::path& path);

}  // namespace swemps::io
