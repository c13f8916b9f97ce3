// Tests of dates and CF time units: what a scene's start_time and a file's time axis say, in
// seconds.

#include <catch2/catch.hpp>

#include "swemps/io/cf_time.hpp"

using namespace swemps::io;

TEST_CASE("ISO dates in seconds since 1970, with zones", "[cf_time]") {
  CHECK(seconds_since_1970(*parse_calendar_time("1970-01-01")) == 0.0);
  CHECK(seconds_since_1970(*parse_calendar_time("2000-03-01T00:00:00Z")) == 951868800.0);
  CHECK(seconds_since_1970(*parse_calendar_time("2024-06-01T12:00:00+02:00")) ==
        seconds_since_1970(*parse_calendar_time("2024-06-01T10:00Z")));
  CHECK(seconds_since_1970(*parse_calendar_time("1969-12-31 23:00")) == -3600.0);
  // What files write: fractions of a second, a space before the zone, UTC.
  CHECK_FALSE(parse_calendar_time("2024-06-01 12:00:00.5"));
  CHECK(parse_calendar_time("2024-06-01 12:00:00.5", true)->second == 0.5);
  CHECK(parse_calendar_time("2024-06-01 12:00:00 +02:00", true)->offset_minutes == 120);
  CHECK(parse_calendar_time("2024-06-01 12:00:00 UTC", true)->zoned);
  CHECK_FALSE(parse_calendar_time("2024-06-01T12:00")->zoned);
  // Dates that do not exist, and other text.
  CHECK_FALSE(parse_calendar_time("2023-02-29"));
  CHECK(parse_calendar_time("2024-02-29"));
  CHECK_FALSE(parse_calendar_time("2024-06-01T25:00"));
  CHECK_FALSE(parse_calendar_time("June 1st"));
  CHECK_FALSE(parse_calendar_time("2024-06-01+2"));
}

TEST_CASE("CF time units: the unit in seconds and the reference date", "[cf_time]") {
  const auto minutes = parse_cf_time_units("minutes since 2024-06-01 12:00:00");
  REQUIRE(minutes);
  CHECK(minutes->seconds_per_unit == 60.0);
  REQUIRE(minutes->since);
  CHECK(minutes->since->hour == 12);
  CHECK(parse_cf_time_units("hours since 1970-01-01")->seconds_per_unit == 3600.0);
  CHECK(parse_cf_time_units("days since 1970-01-01T00:00:00Z")->seconds_per_unit == 86400.0);
  const auto bare = parse_cf_time_units("s");
  REQUIRE(bare);
  CHECK_FALSE(bare->since);
  CHECK_FALSE(parse_cf_time_units("fortnights since 1970-01-01"));
  CHECK_FALSE(parse_cf_time_units("hours since yesterday"));
}
