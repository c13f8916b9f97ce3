#pragma once
// Numbers and durations as a report on a terminal shows them, and its headings and rows.

#include <string>

namespace swemps::cli {

// 12345 -> "12,345": counts a reader compares at a glance; "?" for a number that is not finite.
std::string count(double v);
// Four significant digits, without an exponent between 1e-3 and 1e9 (10,800 s, not 1.08e+04).
std::string num(double v);
// "0.25 s", "4 min 7 s", "2 h 5 min".
std::string duration(double s);
// A blank line, then the title.
void heading(const std::string& title);
// Labels in one column, so that values line up down a section.
void row(const std::string& label, const std::string& value);

}  // namespace swemps::cli
