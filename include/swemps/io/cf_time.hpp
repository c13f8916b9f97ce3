#pragma once
// Dates and CF time units: the "2024-06-01T12:00:00Z" a scene gives for t = 0, and the
// "minutes since 2024-06-01 12:00:00" of a file's time axis, as numbers of seconds.

#include <optional>
#include <string>
#include <string_view>

namespace swemps::io {

struct CalendarTime {
  int year = 1970, month = 1, day = 1, hour = 0, minute = 0;
  double second = 0.0;
  int offset_minutes = 0;  // east of UTC ("+02:00": 120)
  bool zoned = false;      // whether the text gave a zone ("Z", "UTC" or an offset)
};

// An ISO 8601 date and time: "2024-06-01", "2024-06-01T12:00", "2024-06-01T12:00:00", a space
// in place of the "T", each optionally followed by "Z" or an offset "+02:00". With `lenient`,
// also what files write: a fraction of a second, a space before the zone, and " UTC". Empty
// for anything else, or a date that does not exist.
std::optional<CalendarTime> parse_calendar_time(std::string_view text, bool lenient = false);

// Seconds from 1970-01-01T00:00:00Z to `t`, in the proleptic Gregorian calendar.
double seconds_since_1970(const CalendarTime& t);

// The CF units of a time axis, "<unit> since <date>" or a bare "<unit>": seconds, minutes,
// hours or days (and their usual abbreviations, s, sec, min, h, hr, d). `since` is empty for a
// bare unit. Empty for anything else, or for a calendar other than the standard one's dates.
struct CfTimeUnits {
  double seconds_per_unit = 1.0;
  std::optional<CalendarTime> since;
};
std::optional<CfTimeUnits> parse_cf_time_units(std::string_view units);

}  // namespace swemps::io
