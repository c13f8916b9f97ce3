#include "swemps/io/cf_time.hpp"

#include <array>
#include <cmath>
#include <cstdlib>

namespace swemps::io {

namespace {

// `digits` decimal digits at text[at], or -1.
int digits_at(std::string_view text, std::size_t at, std::size_t digits) {
  if (at + digits > text.size()) return -1;
  int value = 0;
  for (std::size_t k = 0; k < digits; ++k) {
    const char c = text[at + k];
    if (c < '0' || c > '9') return -1;
    value = value * 10 + (c - '0');
  }
  return value;
}

bool is_leap(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

// Days from 1970-01-01 to the given date (Howard Hinnant's days-from-civil algorithm).
long long days_from_civil(int y, int m, int d) {
  y -= m <= 2 ? 1 : 0;
  const long long era = (y >= 0 ? y : y - 399) / 400;
  const long long yoe = y - era * 400;
  const long long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const long long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<CalendarTime> parse_calendar_time(std::string_view text, bool lenient) {
  if (lenient) text = trimmed(text);
  CalendarTime t;
  t.year = digits_at(text, 0, 4);
  t.month = digits_at(text, 5, 2);
  t.day = digits_at(text, 8, 2);
  if (t.year < 0 || t.month < 1 || t.month > 12 || t.day < 1 || text[4] != '-' || text[7] != '-')
    return std::nullopt;
  const std::array<int, 12> days = {
      31, is_leap(t.year) ? 29 : 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (t.day > days[static_cast<std::size_t>(t.month - 1)]) return std::nullopt;
  std::size_t at = 10;
  if (at < text.size() && (text[at] == 'T' || text[at] == ' ') && at + 1 < text.size() &&
      text[at + 1] >= '0' && text[at + 1] <= '9') {
    t.hour = digits_at(text, at + 1, 2);
    t.minute = digits_at(text, at + 4, 2);
    if (t.hour < 0 || t.hour > 23 || t.minute < 0 || t.minute > 59 || text[at + 3] != ':')
      return std::nullopt;
    at += 6;
    if (at < text.size() && text[at] == ':') {
      const int whole = digits_at(text, at + 1, 2);
      if (whole < 0 || whole > 59) return std::nullopt;
      t.second = whole;
      at += 3;
      if (lenient && at < text.size() && text[at] == '.') {
        double scale = 0.1;
        for (++at; at < text.size() && text[at] >= '0' && text[at] <= '9'; ++at) {
          t.second += scale * (text[at] - '0');
          scale *= 0.1;
        }
      }
    }
  }
  std::string_view rest = text.substr(std::min(at, text.size()));
  if (lenient) rest = trimmed(rest);
  if (rest.empty()) return t;
  t.zoned = true;
  if (rest == "Z" || (lenient && rest == "UTC")) return t;
  const int zh = digits_at(rest, 1, 2), zm = digits_at(rest, 4, 2);
  if (rest.size() != 6 || (rest[0] != '+' && rest[0] != '-') || rest[3] != ':' || zh < 0 ||
      zh > 14 || zm < 0 || zm > 59) {
    return std::nullopt;
  }
  t.offset_minutes = (rest[0] == '-' ? -1 : 1) * (zh * 60 + zm);
  return t;
}

double seconds_since_1970(const CalendarTime& t) {
  const double days = static_cast<double>(days_from_civil(t.year, t.month, t.day));
  return days * 86400.0 + t.hour * 3600.0 + t.minute * 60.0 + t.second - t.offset_minutes * 60.0;
}

std::optional<CfTimeUnits> parse_cf_time_units(std::string_view units) {
  units = trimmed(units);
  const std::size_t since = units.find(" since ");
  const std::string_view word = trimmed(units.substr(0, since));
  CfTimeUnits out;
  if (word == "seconds" || word == "second" || word == "s" || word == "sec" || word == "secs") {
    out.seconds_per_unit = 1.0;
  } else if (word == "minutes" || word == "minute" || word == "min" || word == "mins") {
    out.seconds_per_unit = 60.0;
  } else if (word == "hours" || word == "hour" || word == "h" || word == "hr" || word == "hrs") {
    out.seconds_per_unit = 3600.0;
  } else if (word == "days" || word == "day" || word == "d") {
    out.seconds_per_unit = 86400.0;
  } else {
    return std::nullopt;
  }
  if (since != std::string_view::npos) {
    out.since = parse_calendar_time(units.substr(since + 7), true);
    if (!out.since) return std::nullopt;
  }
  return out;
}

}  // namespace swemps::io
