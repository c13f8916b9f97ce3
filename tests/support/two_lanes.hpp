#pragma once
// A scene several tests share (tests/scenario/test_provenance.cpp, test_pathlines_run.cpp):
// sources kept apart by a wall, with every way water comes and goes.

#include <nlohmann/json.hpp>

namespace swemps::testing {

// A channel 40 m long split lengthwise by a wall into two lanes, each with a lake at its head
// and a river running into the lake; rain over both; the water leaves through a line near the
// far end. Each lane's lake and river have their own names, so four sources and the rain.
inline nlohmann::json two_lane_channel() {
  return nlohmann::json::parse(R"({
    "name": "two lanes",
    "end_time": 8,
    "domain": {"x_min": 0, "x_max": 40, "y_min": 0, "y_max": 10},
    "walls": [{"polyline": [[40, 0], [0, 0], [0, 10], [40, 10]]},
              {"polyline": [[0, 5], [40, 5]]}],
    "water": [{"name": "north lake", "depth": 0.4, "spacing": 0.5,
               "rectangle": {"x_min": 0, "x_max": 15, "y_min": 5, "y_max": 10}},
              {"name": "south lake", "depth": 0.3, "spacing": 0.5,
               "rectangle": {"x_min": 0, "x_max": 15, "y_min": 0, "y_max": 5}}],
    "inflow": [{"name": "north river", "line": [[0.5, 5.5], [0.5, 9.5]],
                "hydrograph": [[0, 0.4]], "depth": 0.05, "direction": [1, 0], "spacing": 0.5},
               {"name": "south river", "line": [[0.5, 0.5], [0.5, 4.5]],
                "hydrograph": [[0, 0.4]], "depth": 0.05, "direction": [1, 0], "spacing": 0.5}],
    "rain": {"name": "storm", "rate_mm_h": 2000, "spacing": 1},
    "outflow": [{"line": [[30, 0], [30, 10]]}],
    "splitting": {},
    "merging": {},
    "output": {"path": "lanes.nc", "interval": 4, "series_interval": 0.5,
               "grid": {"spacing": 1},
               "gauges": [{"name": "north", "x": 10, "y": 7.5}, {"name": "dry", "x": 39, "y": 2}],
               "provenance": {"sources": true, "age": true}}
  })");
}

}  // namespace swemps::testing
