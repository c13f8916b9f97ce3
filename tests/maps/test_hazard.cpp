// Tests of the flood hazard of one cell: the debris-factor table branch by branch, hand-worked
// hazard ratings, every class boundary from both sides, each Australian class with each of its
// three limits binding, the dry cell, rejected inputs, and monotonicity over a grid (which is
// what makes the hazard of the peak depth and peak speed an upper bound of the peak hazard).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "swemps/maps/hazard.hpp"

using swemps::maps::aidr_hazard;
using swemps::maps::AidrHazard;
using swemps::maps::debris_factor;
using swemps::maps::LandUse;
using swemps::maps::uk_hazard_class;
using swemps::maps::uk_hazard_rating;
using swemps::maps::UkHazardClass;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The next double above / below x: "just over" and "just under" a boundary.
double above(double x) { return std::nextafter(x, kInf); }
double below(double x) { return std::nextafter(x, -kInf); }

const LandUse kLandUses[] = {LandUse::pasture_arable, LandUse::woodland, LandUse::urban};

struct Row {
  double pasture, woodland, urban;
};
void check_row(double depth_m, double speed_m_s, Row expected) {
  INFO("d = " << depth_m << " m, v = " << speed_m_s << " m/s");
  CHECK(debris_factor(depth_m, speed_m_s, LandUse::pasture_arable) == expected.pasture);
  CHECK(debris_factor(depth_m, speed_m_s, LandUse::woodland) == expected.woodland);
  CHECK(debris_factor(depth_m, speed_m_s, LandUse::urban) == expected.urban);
}

}  // namespace

TEST_CASE("Debris factor follows the guidance table band by band", "[maps][hazard]") {
  const Row shallow{0.0, 0.0, 0.0}, middle{0.0, 0.5, 1.0}, deep_or_fast{0.5, 1.0, 1.0};

  SECTION("0 to 0.25 m, 0.25 m itself included") {
    check_row(0.1, 1.0, shallow);
    check_row(0.25, 0.0, shallow);
    check_row(0.25, 2.0, shallow);
  }
  SECTION("0.25 to 0.75 m, 0.75 m itself included") {
    check_row(above(0.25), 0.0, middle);
    check_row(0.5, 1.0, middle);
    check_row(0.75, 2.0, middle);
  }
  SECTION("deeper than 0.75 m") {
    check_row(above(0.75), 0.0, deep_or_fast);
    check_row(3.0, 0.5, deep_or_fast);
  }
  SECTION("faster than 2 m/s at any depth, 2 m/s itself not") {
    check_row(0.1, 2.0, shallow);
    check_row(0.1, above(2.0), deep_or_fast);
    check_row(0.5, 2.0, middle);
    check_row(0.5, 2.5, deep_or_fast);
    check_row(0.01, 6.0, deep_or_fast);
  }
  SECTION("a dry cell carries no debris, whatever its speed") {
    check_row(0.0, 0.0, shallow);
    check_row(0.0, 5.0, shallow);
    check_row(-0.0, 5.0, shallow);
  }
}

TEST_CASE("Hazard rating of hand-worked cells", "[maps][hazard]") {
  // One cell, three land uses, three classes. d = 0.6 m is in the 0.25-0.75 m band:
  // pasture   HR = 0.6 x (1.5 + 0.5) + 0   = 1.2 -> moderate
  // woodland  HR = 0.6 x (1.5 + 0.5) + 0.5 = 1.7 -> significant
  // urban     HR = 0.6 x (1.5 + 0.5) + 1   = 2.2 -> extreme
  CHECK(uk_hazard_rating(0.6, 1.5, LandUse::pasture_arable) == Approx(1.2));
  CHECK(uk_hazard_rating(0.6, 1.5, LandUse::woodland) == Approx(1.7));
  CHECK(uk_hazard_rating(0.6, 1.5, LandUse::urban) == Approx(2.2));
  CHECK(uk_hazard_class(uk_hazard_rating(0.6, 1.5, LandUse::pasture_arable)) ==
        UkHazardClass::moderate);
  CHECK(uk_hazard_class(uk_hazard_rating(0.6, 1.5, LandUse::woodland)) ==
        UkHazardClass::significant);
  CHECK(uk_hazard_class(uk_hazard_rating(0.6, 1.5, LandUse::urban)) == UkHazardClass::extreme);

  // Deep, slow water on pasture: d = 1.0 > 0.75 so DF = 0.5; HR = 1.0 x 0.7 + 0.5 = 1.2.
  CHECK(uk_hazard_rating(1.0, 0.2, LandUse::pasture_arable) == Approx(1.2));
  // Shallow, fast water: v = 3 > 2 so the deep-or-fast row applies at 0.2 m.
  // pasture HR = 0.2 x 3.5 + 0.5 = 1.2 (moderate); urban HR = 0.2 x 3.5 + 1 = 1.7 (significant).
  CHECK(uk_hazard_rating(0.2, 3.0, LandUse::pasture_arable) == Approx(1.2));
  CHECK(uk_hazard_rating(0.2, 3.0, LandUse::urban) == Approx(1.7));
  CHECK(uk_hazard_class(uk_hazard_rating(0.2, 3.0, LandUse::urban)) == UkHazardClass::significant);
  // Ankle-deep still water on pasture: HR = 0.3 x (0 + 0.5) + 0 = 0.15 -> low.
  CHECK(uk_hazard_rating(0.3, 0.0, LandUse::pasture_arable) == Approx(0.15));
  // Deep woodland flow: HR = 2.0 x (1.0 + 0.5) + 1 = 4 -> extreme.
  CHECK(uk_hazard_rating(2.0, 1.0, LandUse::woodland) == Approx(4.0));
  // A thin film: HR = 0.01 x 0.5 + 0 = 0.005.
  CHECK(uk_hazard_rating(0.01, 0.0, LandUse::urban) == Approx(0.005));

  // A dry cell: HR = 0 x (v + 0.5) + DF(0) = 0, low, for every land use and speed.
  for (const LandUse land : kLandUses) {
    CHECK(uk_hazard_rating(0.0, 0.0, land) == 0.0);
    CHECK(uk_hazard_rating(0.0, 3.0, land) == 0.0);
    CHECK(uk_hazard_class(uk_hazard_rating(0.0, 3.0, land)) == UkHazardClass::low);
  }
}

TEST_CASE("UK hazard classes at and beside every boundary", "[maps][hazard]") {
  CHECK(uk_hazard_class(0.0) == UkHazardClass::low);
  CHECK(uk_hazard_class(below(0.75)) == UkHazardClass::low);
  CHECK(uk_hazard_class(0.75) == UkHazardClass::moderate);  // "less than 0.75" is low
  CHECK(uk_hazard_class(1.0) == UkHazardClass::moderate);
  CHECK(uk_hazard_class(1.25) == UkHazardClass::moderate);  // our reading of the shared end
  CHECK(uk_hazard_class(above(1.25)) == UkHazardClass::significant);
  CHECK(uk_hazard_class(2.0) == UkHazardClass::significant);  // "more than 2.0" is extreme
  CHECK(uk_hazard_class(above(2.0)) == UkHazardClass::extreme);
  CHECK(uk_hazard_class(1.0e6) == UkHazardClass::extreme);

  // Cells that land exactly on a boundary, in exact binary arithmetic:
  // pasture d = 0.5, v = 1.0: HR = 0.5 x 1.5 + 0 = 0.75 -> moderate
  // pasture d = 0.5, v = 2.0: HR = 0.5 x 2.5 + 0 = 1.25 -> moderate (2 m/s is not "> 2")
  // urban   d = 0.5, v = 1.5: HR = 0.5 x 2.0 + 1 = 2.0  -> significant
  REQUIRE(uk_hazard_rating(0.5, 1.0, LandUse::pasture_arable) == 0.75);
  REQUIRE(uk_hazard_rating(0.5, 2.0, LandUse::pasture_arable) == 1.25);
  REQUIRE(uk_hazard_rating(0.5, 1.5, LandUse::urban) == 2.0);
  CHECK(uk_hazard_class(uk_hazard_rating(0.5, 1.0, LandUse::pasture_arable)) ==
        UkHazardClass::moderate);
  CHECK(uk_hazard_class(uk_hazard_rating(0.5, 2.0, LandUse::pasture_arable)) ==
        UkHazardClass::moderate);
  CHECK(uk_hazard_class(uk_hazard_rating(0.5, 1.5, LandUse::urban)) == UkHazardClass::significant);
  // Just faster than 2 m/s the pasture cell above takes DF = 0.5 and jumps a class:
  // HR = 0.5 x 2.5 + 0.5 = 1.75 -> significant.
  CHECK(uk_hazard_rating(0.5, above(2.0), LandUse::pasture_arable) == Approx(1.75));
  CHECK(uk_hazard_class(uk_hazard_rating(0.5, above(2.0), LandUse::pasture_arable)) ==
        UkHazardClass::significant);

  // The values written to class maps.
  CHECK(static_cast<int>(UkHazardClass::low) == 1);
  CHECK(static_cast<int>(UkHazardClass::extreme) == 4);
}

TEST_CASE("Australian classes H1-H6, each limit binding on each side", "[maps][hazard]") {
  SECTION("H1: d <= 0.3, v <= 2, dv <= 0.3") {
    CHECK(aidr_hazard(0.1, 1.0) == AidrHazard::h1);
    CHECK(aidr_hazard(0.3, 1.0) == AidrHazard::h1);         // dv = 0.3 on the limit too
    CHECK(aidr_hazard(above(0.3), 0.0) == AidrHazard::h2);  // depth binds
    // dv binds: 0.25 x 1.2 = 0.3 exactly; a hair faster is over it.
    REQUIRE(0.25 * 1.2 == 0.3);
    CHECK(aidr_hazard(0.25, 1.2) == AidrHazard::h1);
    CHECK(aidr_hazard(0.25, above(1.2)) == AidrHazard::h2);
    // Speed binds, and skips to H5: 0.1 m at just over 2 m/s fails every 2 m/s limit.
    CHECK(aidr_hazard(0.1, 2.0) == AidrHazard::h1);
    CHECK(aidr_hazard(0.1, above(2.0)) == AidrHazard::h5);
  }
  SECTION("H2: d <= 0.5, v <= 2, dv <= 0.6") {
    REQUIRE(0.5 * 1.2 == 0.6);
    CHECK(aidr_hazard(0.4, 0.5) == AidrHazard::h2);         // dv = 0.2, depth over H1's 0.3
    CHECK(aidr_hazard(0.5, 1.2) == AidrHazard::h2);         // depth and dv both on their limits
    CHECK(aidr_hazard(above(0.5), 0.0) == AidrHazard::h3);  // depth binds
    CHECK(aidr_hazard(0.5, above(1.2)) == AidrHazard::h4);  // dv binds, and H3 shares 0.6
    // d = 0.4, v = 1.6: depth alone says H2, but dv = 0.64 > 0.6 rules out H2 and H3;
    // H4 holds (0.4 <= 2, 1.6 <= 2, 0.64 <= 1.0).
    CHECK(aidr_hazard(0.4, 1.6) == AidrHazard::h4);
  }
  SECTION("H3: d <= 1.2, v <= 2, dv <= 0.6") {
    REQUIRE(1.2 * 0.5 == 0.6);
    CHECK(aidr_hazard(0.8, 0.5) == AidrHazard::h3);         // dv = 0.4
    CHECK(aidr_hazard(1.2, 0.5) == AidrHazard::h3);         // depth and dv on their limits
    CHECK(aidr_hazard(above(1.2), 0.0) == AidrHazard::h4);  // depth binds
    CHECK(aidr_hazard(1.2, above(0.5)) == AidrHazard::h4);  // dv binds
  }
  SECTION("H4: d <= 2, v <= 2, dv <= 1") {
    CHECK(aidr_hazard(2.0, 0.5) == AidrHazard::h4);         // depth and dv on their limits
    CHECK(aidr_hazard(above(2.0), 0.0) == AidrHazard::h5);  // depth binds
    CHECK(aidr_hazard(1.0, 1.0) == AidrHazard::h4);
    CHECK(aidr_hazard(1.0, above(1.0)) == AidrHazard::h5);  // dv binds
    CHECK(aidr_hazard(0.5, 2.0) == AidrHazard::h4);         // speed and dv on their limits
    CHECK(aidr_hazard(0.4, above(2.0)) == AidrHazard::h5);  // speed binds (dv = 0.8)
  }
  SECTION("H5: d <= 4, v <= 4, dv <= 4; H6 beyond") {
    CHECK(aidr_hazard(3.0, 1.0) == AidrHazard::h5);
    CHECK(aidr_hazard(4.0, 1.0) == AidrHazard::h5);
    CHECK(aidr_hazard(above(4.0), 0.0) == AidrHazard::h6);  // depth alone: a deep still pool
    CHECK(aidr_hazard(1.0, 4.0) == AidrHazard::h5);
    CHECK(aidr_hazard(0.1, above(4.0)) == AidrHazard::h6);  // speed alone
    CHECK(aidr_hazard(2.0, 2.0) == AidrHazard::h5);         // dv = 4 on the limit
    CHECK(aidr_hazard(2.0, above(2.0)) == AidrHazard::h6);  // dv binds
    CHECK(aidr_hazard(10.0, 5.0) == AidrHazard::h6);
  }
  SECTION("a dry cell is H1 whatever its speed; a film is not") {
    CHECK(aidr_hazard(0.0, 0.0) == AidrHazard::h1);
    CHECK(aidr_hazard(0.0, 3.0) == AidrHazard::h1);
    CHECK(aidr_hazard(0.001, 3.0) == AidrHazard::h5);  // why callers screen films out
  }
  CHECK(static_cast<int>(AidrHazard::h1) == 1);
  CHECK(static_cast<int>(AidrHazard::h6) == 6);
}

TEST_CASE("Hazard functions reject what is not a depth, speed or rating", "[maps][hazard]") {
  for (const double bad : {kNaN, kInf, -kInf, -1.0, -1e-300}) {
    INFO("bad = " << bad);
    CHECK_THROWS_AS(debris_factor(bad, 1.0, LandUse::urban), std::invalid_argument);
    CHECK_THROWS_AS(debris_factor(1.0, bad, LandUse::urban), std::invalid_argument);
    CHECK_THROWS_AS(uk_hazard_rating(bad, 1.0, LandUse::woodland), std::invalid_argument);
    CHECK_THROWS_AS(uk_hazard_rating(1.0, bad, LandUse::woodland), std::invalid_argument);
    CHECK_THROWS_AS(aidr_hazard(bad, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(aidr_hazard(1.0, bad), std::invalid_argument);
    CHECK_THROWS_AS(uk_hazard_class(bad), std::invalid_argument);
  }
  CHECK_THROWS_AS(debris_factor(1.0, 1.0, static_cast<LandUse>(7)), std::invalid_argument);
}

TEST_CASE("Hazard never falls as depth or speed rises", "[maps][hazard]") {
  // A grid through every boundary and beyond; each step is one cell deeper or faster.
  std::vector<double> depths, speeds;
  for (int i = 0; i <= 500; ++i) depths.push_back(0.01 * i);  // 0 to 5 m
  for (int j = 0; j <= 500; ++j) speeds.push_back(0.01 * j);  // 0 to 5 m/s
  for (const LandUse land : kLandUses) {
    for (std::size_t i = 0; i < depths.size(); ++i) {
      for (std::size_t j = 0; j < speeds.size(); ++j) {
        const double d = depths[i], v = speeds[j];
        const double hr = uk_hazard_rating(d, v, land);
        const auto h = aidr_hazard(d, v);
        if (i + 1 < depths.size()) {
          REQUIRE(uk_hazard_rating(depths[i + 1], v, land) >= hr);
          REQUIRE(aidr_hazard(depths[i + 1], v) >= h);
        }
        if (j + 1 < speeds.size()) {
          REQUIRE(uk_hazard_rating(d, speeds[j + 1], land) >= hr);
          REQUIRE(aidr_hazard(d, speeds[j + 1]) >= h);
        }
      }
    }
  }
  // More debris in woodland than on pasture, and in towns than in woodland, everywhere.
  for (const double d : depths) {
    for (const double v : speeds) {
      REQUIRE(debris_factor(d, v, LandUse::pasture_arable) <=
              debris_factor(d, v, LandUse::woodland));
      REQUIRE(debris_factor(d, v, LandUse::woodland) <= debris_factor(d, v, LandUse::urban));
    }
  }
}

TEST_CASE("Peak hazard over time is below the hazard of peak depth and peak speed",
          "[maps][hazard]") {
  // The worked example of the docs. One cell, two times:
  //   t1: d = 1.0 m, v = 0.2 m/s (deep, slow)     t2: d = 0.2 m, v = 1.4 m/s (shallow, fast)
  // Over time (pasture):
  //   t1: DF = 0.5 (d > 0.75), HR = 1.0 x 0.7 + 0.5 = 1.2  -> moderate; dv = 0.2, d > 0.5 -> H3
  //   t2: DF = 0,              HR = 0.2 x 1.9       = 0.38 -> low;   dv = 0.28, d <= 0.3 -> H1
  //   maximum: HR = 1.2 (moderate), H3.
  // From the separate maximum maps, d = 1.0 and v = 1.4, a state that never happened:
  //   HR = 1.0 x 1.9 + 0.5 = 2.4 -> extreme; dv = 1.4 > 1.0 -> H5.
  const LandUse land = LandUse::pasture_arable;
  const double hr_t1 = uk_hazard_rating(1.0, 0.2, land), hr_t2 = uk_hazard_rating(0.2, 1.4, land);
  CHECK(hr_t1 == Approx(1.2));
  CHECK(hr_t2 == Approx(0.38));
  CHECK(uk_hazard_class(std::max(hr_t1, hr_t2)) == UkHazardClass::moderate);
  CHECK(aidr_hazard(1.0, 0.2) == AidrHazard::h3);
  CHECK(aidr_hazard(0.2, 1.4) == AidrHazard::h1);

  const double hr_peaks = uk_hazard_rating(1.0, 1.4, land);
  CHECK(hr_peaks == Approx(2.4));
  CHECK(uk_hazard_class(hr_peaks) == UkHazardClass::extreme);
  CHECK(aidr_hazard(1.0, 1.4) == AidrHazard::h5);
}

TEST_CASE("Hazard class names for metadata", "[maps][hazard]") {
  using swemps::maps::name;
  CHECK(name(AidrHazard::h1) == "H1: generally safe for vehicles, people and buildings");
  CHECK(name(AidrHazard::h2) == "H2: unsafe for small vehicles");
  CHECK(name(UkHazardClass::moderate) == "moderate: danger for some");
  CHECK(name(LandUse::pasture_arable) == "pasture/arable");

  std::set<std::string> names;
  for (int k = 1; k <= 6; ++k) {
    const std::string n(name(static_cast<AidrHazard>(k)));
    CHECK(n.rfind("H" + std::to_string(k) + ": ", 0) == 0);
    names.insert(n);
  }
  for (int k = 1; k <= 4; ++k) names.insert(std::string(name(static_cast<UkHazardClass>(k))));
  for (const LandUse land : kLandUses) names.insert(std::string(name(land)));
  CHECK(names.size() == 6 + 4 + 3);
}
