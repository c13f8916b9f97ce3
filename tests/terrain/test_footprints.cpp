// Tests of building footprints: which points lie under a building (holes and overlaps
// included), that the index agrees with a test of every footprint, and raising a bed under
// them.

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "swemps/terrain/footprints.hpp"

using namespace swemps::terrain;

namespace {

Ring square(double x0, double y0, double side) {
  return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

}  // namespace

TEST_CASE("a footprint holds the points inside its outer ring and outside its holes", "[terrain]") {
  const Footprints f({{square(0.0, 0.0, 10.0), {square(4.0, 4.0, 2.0)}},
                      {{{20.0, 0.0}, {30.0, 0.0}, {25.0, 8.0}}, {}}});
  CHECK(f.size() == 2);
  CHECK(f.contains(1.0, 1.0));
  CHECK_FALSE(f.contains(5.0, 5.0));  // the courtyard
  CHECK(f.contains(3.9, 5.0));
  CHECK(f.footprint_at(25.0, 2.0) == 1);
  CHECK_FALSE(f.contains(21.0, 6.0));  // beside the triangle's slope
  CHECK_FALSE(f.contains(15.0, 5.0));
  CHECK_FALSE(f.contains(-1.0, 5.0));
  CHECK_FALSE(f.contains(100.0, 100.0));
  CHECK_FALSE(f.contains(NAN, 1.0));
  CHECK_FALSE(Footprints{}.contains(0.0, 0.0));
}

TEST_CASE("the footprint index agrees with a test of every footprint", "[terrain]") {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> at(0.0, 500.0), side(3.0, 30.0);
  std::vector<Footprint> all;
  for (int k = 0; k < 300; ++k) all.push_back({square(at(random), at(random), side(random)), {}});
  const Footprints f(all);
  int inside = 0;
  for (int q = 0; q < 20000; ++q) {
    const double x = at(random), y = at(random);
    bool brute = false;
    for (const auto& footprint : all) brute = brute || ring_contains(footprint.outer, x, y);
    inside += brute ? 1 : 0;
    CHECK(f.contains(x, y) == brute);
  }
  CHECK(inside > 1000);
}

TEST_CASE("raising footprints lifts the cells whose centres they hold", "[terrain]") {
  GridGeometry g;
  g.columns = 10;
  g.rows = 10;
  g.x_left = 0.0;
  g.y_top = 10.0;
  g.cell_width = g.cell_height = 1.0;
  std::vector<double> z(100, 1.0);
  z[0] = NAN;  // nodata stays nodata
  const GriddedField bed(g, z, "", "bed elevation");
  // A 3 x 2 block over cell centres x 2.5-4.5, y 2.5-3.5; one footprint between centres.
  const Footprints f({{{{2.0, 2.0}, {5.0, 2.0}, {5.0, 4.0}, {2.0, 4.0}}, {}},
                      {{{7.1, 7.1}, {7.4, 7.1}, {7.4, 7.4}}, {}},
                      {square(-0.5, 9.0, 1.5), {}}});
  const auto raised = raise_footprints(bed, f, 10.0);
  CHECK(raised.cells_raised == 6);
  CHECK(raised.footprints_missed == 1);
  CHECK(raised.field.sample(3.5, 3.0) == Approx(11.0));
  CHECK(raised.field.sample(5.5, 3.0) == Approx(1.0));
  CHECK(std::isnan(raised.field.at(0, 0)));
  CHECK(raised.field.name() == "bed elevation");
}

TEST_CASE("footprints refuse rings of fewer than 3 vertices or non-finite ones", "[terrain]") {
  CHECK_THROWS_AS(Footprints({{{{0.0, 0.0}, {1.0, 0.0}}, {}}}), std::invalid_argument);
  CHECK_THROWS_AS(Footprints({{{{0.0, 0.0}, {1.0, 0.0}, {INFINITY, 1.0}}, {}}}),
                  std::invalid_argument);
  CHECK_THROWS_AS(Footprints({{square(0.0, 0.0, 1.0), {{{0.0, 0.0}}}}}), std::invalid_argument);
}
