// NTHMP benchmark problem 6, case B (a solitary wave, H/d = 0.096, round a conical island;
// Briggs et al. 1995) run by the command users run: the shipped cases/nthmp-bp6/case-b.json as
// it is (0.1 m particles; about two minutes on one thread, so tagged [long]), scored as
// tools/nthmp_bp6.py scores it (docs/tsunami.md): each gauge's maximum wave height and the
// maximum run-up round the island against the basin's, within the 10 % the NTHMP allows
// against laboratory data. Case B is the case that meets every one of these at 0.1 m; A and C
// miss some, for reasons docs/tsunami.md measures.

#include <gdal_priv.h>
#include <netcdf.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/netcdf_values.hpp"
#include "../support/run_command.hpp"
#include "../support/temp_dir.hpp"
#include "swemps/io/gdal_messages.hpp"

namespace fs = std::filesystem;
using swemps::testing::whole_variable;

namespace {

const fs::path kSource = SWEMPS_SOURCE_DIR;
constexpr std::array<double, 2> kIslandCentre{12.96, 13.80};
constexpr std::size_t kGauges = 8;  // g1-g4, g6, g9, g16, g22: the lab's column order
constexpr double kPi = 3.14159265358979323846;

std::vector<std::vector<double>> numeric_rows(const fs::path& file, std::size_t width) {
  std::ifstream in(file);
  REQUIRE(in.good());
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::vector<double> row;
    for (std::string word; fields >> word;) {
      char* end = nullptr;
      const double value = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') break;
      row.push_back(value);
    }
    if (row.size() == width) rows.push_back(std::move(row));
  }
  return rows;
}

// Linear interpolation of (t, y) at `time`, t ascending; the end values outside.
double interpolate(const std::vector<double>& t, const std::vector<double>& y, double time) {
  const auto after = std::upper_bound(t.begin(), t.end(), time);
  if (after == t.begin()) return y.front();
  if (after == t.end()) return y.back();
  const std::size_t k = static_cast<std::size_t>(after - t.begin());
  const double w = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return (1.0 - w) * y[k - 1] + w * y[k];
}

// The ground where the radius at `degrees` (0 towards -y, 90 towards +x) last crosses the
// line, or NaN where it does not.
double runup_along(const std::vector<std::array<double, 3>>& line, double degrees) {
  const double theta = degrees * kPi / 180.0;
  const std::array<double, 2> direction{std::sin(theta), -std::cos(theta)};
  double best = std::nan(""), reach_best = -1e300;
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const auto side = [&](std::size_t m) {
      return -(line[m][0] - kIslandCentre[0]) * direction[1] +
             (line[m][1] - kIslandCentre[1]) * direction[0];
    };
    const auto along = [&](std::size_t m) {
      return (line[m][0] - kIslandCentre[0]) * direction[0] +
             (line[m][1] - kIslandCentre[1]) * direction[1];
    };
    const double s0 = side(k), s1 = side(k + 1);
    if (s0 == s1 || s0 * s1 > 0.0) continue;
    const double w = s0 / (s0 - s1);
    const double reach = along(k) + w * (along(k + 1) - along(k));
    if (reach > reach_best) {
      reach_best = reach;
      best = line[k][2] + w * (line[k + 1][2] - line[k][2]);
    }
  }
  return best;
}

}  // namespace

TEST_CASE("NTHMP benchmark problem 6, case B: gauges and run-up round a conical island",
          "[verification][tsunami][long]") {
  swemps::testing::TempDir dir("bp6");
  nlohmann::json scene;
  std::ifstream(kSource / "cases/nthmp-bp6/case-b.json") >> scene;
  scene["bed"]["raster"] = (kSource / "data/nthmp-bp6/conical_island.asc").string();
  scene["output"]["path"] = (dir.path() / "bp6.nc").string();
  scene["output"].erase("interval");
  std::ofstream(dir.path() / "bp6.json") << scene.dump(2);
  const auto r = swemps::testing::run_command(
      std::string(SWEMPS_CLI) + " run " + (dir.path() / "bp6.json").string() + " --threads 2 -q");
  INFO(r.output);
  REQUIRE(r.status == 0);

  int nc = -1;
  REQUIRE(nc_open((dir.path() / "bp6.nc").c_str(), NC_NOWRITE, &nc) == NC_NOERR);
  const auto gauge_x = whole_variable(nc, "gauge_x");
  const auto model_time = whole_variable(nc, "series_time");
  const auto level = whole_variable(nc, "gauge_surface_elevation");  // [time][gauge]
  nc_close(nc);
  REQUIRE(gauge_x.size() == kGauges);
  REQUIRE(level.size() == model_time.size() * kGauges);

  // The model's gauges, each less its still level: its reading at t = 0 less the starting
  // wave's rise there (the gauges on the island's face read the still water within 2 mm).
  const auto& wave = scene["water"][0]["solitary_wave"];
  const double height = wave["height"], depth = wave["depth"], crest = wave["crest"][0];
  const double gamma = std::sqrt(3.0 * height / (4.0 * depth));
  std::vector<std::vector<double>> model(kGauges, std::vector<double>(model_time.size()));
  for (std::size_t g = 0; g < kGauges; ++g) {
    const double rise = height / std::pow(std::cosh(gamma * (gauge_x[g] - crest) / depth), 2);
    for (std::size_t k = 0; k < model_time.size(); ++k)
      model[g][k] = level[k * kGauges + g] - (level[g] - rise);
  }
  // The basin's, each less its mean over the first two seconds.
  const auto rows = numeric_rows(kSource / "data/nthmp-bp6/ts2b.txt", 1 + kGauges);
  REQUIRE(rows.size() > 1000);
  std::vector<double> lab_time;
  std::vector<std::vector<double>> lab(kGauges);
  for (const auto& row : rows) {
    lab_time.push_back(row[0]);
    for (std::size_t g = 0; g < kGauges; ++g) lab[g].push_back(row[1 + g]);
  }
  for (auto& series : lab) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < lab_time.size() && lab_time[k] < lab_time[0] + 2.0; ++k, ++n)
      sum += series[k];
    for (double& v : series) v -= sum / static_cast<double>(n);
  }
  // The model's clock runs from the crest's passage at gauge 2, the incident-wave gauge.
  const auto peak = [](const std::vector<double>& v) {
    return static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin());
  };
  const double shift = lab_time[peak(lab[1])] - model_time[peak(model[1])];
  const double start = lab_time[peak(lab[1])] - 3.0, end = model_time.back() + shift;
  std::vector<double> shifted(model_time);
  for (double& t : shifted) t += shift;

  // Maximum wave height at every gauge. Measured at 0.1 m: +2.9, +2.6, +1.6, +2.3, +5.1, +8.1,
  // +1.9 and -6.0 %.
  const std::array<const char*, kGauges> names{"g1", "g2", "g3", "g4", "g6", "g9", "g16", "g22"};
  for (std::size_t g = 0; g < kGauges; ++g) {
    double lab_max = -1.0, model_max = -1.0;
    for (std::size_t k = 0; k < lab_time.size(); ++k) {
      if (lab_time[k] < start || lab_time[k] > end) continue;
      lab_max = std::max(lab_max, lab[g][k]);
      model_max = std::max(model_max, interpolate(shifted, model[g], lab_time[k]));
    }
    INFO(names[g] << ": basin " << lab_max << " m, model " << model_max << " m");
    CHECK(model_max == Approx(lab_max).epsilon(0.10));
  }

  // Maximum run-up: along each of the basin's radii, the ground where the radius crosses the
  // inundation line round the island. Measured at 0.1 m: -2.8 % of the basin's largest.
  swemps::io::register_gdal_drivers();
  const fs::path line_file = dir.path() / "bp6_inundation_line.geojson";
  const GDALDatasetUniquePtr lines(
      GDALDataset::Open(line_file.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  REQUIRE(lines);
  std::vector<std::array<double, 3>> island;
  double island_distance = 1e300;
  for (auto& feature : *lines->GetLayer(0)) {
    const auto* curve = feature->GetGeometryRef()->toLineString();
    std::vector<std::array<double, 3>> points;
    double distance = 0.0;
    for (int k = 0; k < curve->getNumPoints(); ++k) {
      points.push_back({curve->getX(k), curve->getY(k), curve->getZ(k)});
      distance += std::hypot(curve->getX(k) - kIslandCentre[0], curve->getY(k) - kIslandCentre[1]);
    }
    distance /= std::max(1, curve->getNumPoints());
    if (distance < island_distance) {
      island_distance = distance;
      island = std::move(points);
    }
  }
  REQUIRE(island.size() > 10);
  const auto runups = numeric_rows(kSource / "data/nthmp-bp6/run2b.txt", 4);
  REQUIRE(runups.size() >= 20);
  double lab_largest = 0.0, model_largest = 0.0;
  for (const auto& row : runups) {
    lab_largest = std::max(lab_largest, row[2] / 100.0);  // cm
    const double model_runup = runup_along(island, row[1]);
    if (std::isfinite(model_runup)) model_largest = std::max(model_largest, model_runup);
  }
  INFO("maximum run-up: basin " << lab_largest << " m, model " << model_largest << " m");
  CHECK(model_largest == Approx(lab_largest).epsilon(0.10));
}
