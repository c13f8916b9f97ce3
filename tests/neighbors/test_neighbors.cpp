// Tests of the cell-list neighbour search. The O(N^2) brute force is the reference: it is
// simple enough to trust once it passes the hand-worked case below, and the cell list must
// reproduce it exactly (same index sets per row) on random sets and on the awkward ones:
// pairs at exactly the search radius, points on cell edges and on the box edge, coincident
// points, empty cells and cells widened by an outlier.

#include <omp.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "swemps/neighbors/cell_list.hpp"
#include "swemps/neighbors/neighbor_list.hpp"
#include "swemps/neighbors/parallel.hpp"
#include "swemps/neighbors/row_repair.hpp"

namespace nb = swemps::neighbors;

namespace {

// Loops over fewer targets than the parallel threshold run on one thread, so the sets
// meant to exercise the threaded path must be larger than it.
constexpr std::size_t large_n = 5000;
static_assert(large_n > static_cast<std::size_t>(swemps::parallel_threshold) + 1000);

template <int Dim>
struct Points {
  std::array<std::vector<double>, Dim> x;

  std::size_t size() const { return x[0].size(); }
  void add(const std::array<double, Dim>& p) {
    for (int d = 0; d < Dim; ++d) x[d].push_back(p[d]);
  }
  std::array<double, Dim> at(std::size_t i) const {
    std::array<double, Dim> p{};
    for (int d = 0; d < Dim; ++d) p[d] = x[d][i];
    return p;
  }
  nb::Coordinates<Dim> coords() const {
    nb::Coordinates<Dim> c;
    for (int d = 0; d < Dim; ++d) c[d] = std::span<const double>(x[d]);
    return c;
  }
};

// Uniform points in the box [lo, lo + extent]^Dim. The box is off the origin so that the
// cell list's origin is not 0 and the subtraction in the binning is exercised.
template <int Dim>
Points<Dim> random_points(std::size_t n, std::uint32_t seed, double lo = -0.37,
                          double extent = 1.0) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(lo, lo + extent);
  Points<Dim> pts;
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, Dim> p{};
    for (int d = 0; d < Dim; ++d) p[d] = u(gen);
    pts.add(p);
  }
  return pts;
}

// Points origin + (i, j, k) * spacing, computed the way a particle seeder would, so the
// rounding of the products puts many pairs a hair on either side of the spacing.
template <int Dim>
Points<Dim> lattice(int per_side, double spacing, double origin) {
  Points<Dim> pts;
  std::array<int, Dim> idx{};
  for (;;) {
    std::array<double, Dim> p{};
    for (int d = 0; d < Dim; ++d) p[d] = origin + idx[d] * spacing;
    pts.add(p);
    int d = 0;
    while (d < Dim && ++idx[d] == per_side) idx[d++] = 0;
    if (d == Dim) break;
  }
  return pts;
}

template <int Dim>
nb::NeighborList cell_list_neighbors(const Points<Dim>& pts, std::size_t targets, double radius,
                                     double min_cell_width, int subdivisions = 1) {
  nb::CellList<Dim> cells;
  cells.build(pts.coords(), min_cell_width, subdivisions);
  nb::NeighborList out;
  nb::build_neighbor_list<Dim>(cells, pts.coords(), targets, radius, out);
  return out;
}

std::vector<std::uint32_t> sorted_row(const nb::NeighborList& list, std::size_t i) {
  const auto row = list.row(i);
  std::vector<std::uint32_t> v(row.begin(), row.end());
  std::sort(v.begin(), v.end());
  return v;
}

std::string describe(const std::vector<std::uint32_t>& v) {
  std::ostringstream s;
  s << '{';
  for (std::size_t k = 0; k < v.size(); ++k) s << (k ? " " : "") << v[k];
  s << '}';
  return s.str();
}

// Empty when every row holds the same index set in both lists; otherwise the first row
// that differs, so a failure names the offending point instead of just "false".
std::string first_difference(const nb::NeighborList& fast, const nb::NeighborList& reference) {
  if (fast.row_count() != reference.row_count()) {
    return "row counts " + std::to_string(fast.row_count()) + " vs " +
           std::to_string(reference.row_count());
  }
  for (std::size_t i = 0; i < reference.row_count(); ++i) {
    const auto a = sorted_row(fast, i);
    const auto b = sorted_row(reference, i);
    if (a != b) {
      return "row " + std::to_string(i) + ": cell list " + describe(a) + ", brute force " +
             describe(b);
    }
  }
  return {};
}

// Builds both lists and compares them; returns the number of neighbour entries so callers
// can make sure a case is not vacuous (two empty lists always agree).
template <int Dim>
std::size_t check_against_brute_force(const Points<Dim>& pts, std::size_t targets, double radius,
                                      double min_cell_width, int subdivisions = 1,
                                      const nb::NeighborList* known = nullptr) {
  const auto fast = cell_list_neighbors<Dim>(pts, targets, radius, min_cell_width, subdivisions);
  const auto computed =
      known ? nb::NeighborList{} : nb::brute_force_neighbors<Dim>(pts.coords(), targets, radius);
  const auto& reference = known ? *known : computed;
  CHECK(fast.row_count() == targets);
  CHECK(reference.row_count() == targets);
  CHECK(first_difference(fast, reference) == "");
  return reference.index.size();
}

template <int Dim>
std::vector<std::uint32_t> candidates_of(const nb::CellList<Dim>& cells,
                                         const std::array<double, Dim>& point) {
  std::vector<std::uint32_t> found;
  cells.for_each_candidate(point, [&](std::uint32_t j) { found.push_back(j); });
  return found;
}

template <int Dim>
double distance(const std::array<double, Dim>& a, const std::array<double, Dim>& b) {
  double r2 = 0.0;
  for (int d = 0; d < Dim; ++d) r2 += (a[d] - b[d]) * (a[d] - b[d]);
  return std::sqrt(r2);
}

// Restores the OpenMP thread count even when an assertion aborts the test case, so a
// failure here does not change how later tests run.
class ThreadCountGuard {
 public:
  ThreadCountGuard() : saved_(omp_get_max_threads()) {}
  ~ThreadCountGuard() { omp_set_num_threads(saved_); }
  ThreadCountGuard(const ThreadCountGuard&) = delete;
  ThreadCountGuard& operator=(const ThreadCountGuard&) = delete;

 private:
  int saved_;
};

}  // namespace

TEST_CASE("brute-force reference on a hand-worked 1D set", "[neighbors]") {
  // Distances 0.5 are in, exactly 1.0 is out (strict r < radius), the duplicate of point 1
  // (index 4) sees everything point 1 sees plus point 1 itself.
  Points<1> pts;
  for (double v : {0.0, 0.5, 1.0, 2.0, 0.5}) pts.add({v});
  const std::vector<std::vector<std::uint32_t>> expected{{1, 4}, {0, 2, 4}, {1, 4}, {}, {0, 1, 2}};
  const auto reference = nb::brute_force_neighbors<1>(pts.coords(), pts.size(), 1.0);
  const auto fast = cell_list_neighbors<1>(pts, pts.size(), 1.0, 1.0);
  REQUIRE(reference.row_count() == expected.size());
  REQUIRE(fast.row_count() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CAPTURE(i);
    CHECK(sorted_row(reference, i) == expected[i]);
    CHECK(sorted_row(fast, i) == expected[i]);
  }
}

TEMPLATE_TEST_CASE_SIG("cell-list neighbours equal brute force on random points", "[neighbors]",
                       ((int Dim), Dim), 1, 2, 3) {
  const std::size_t n = GENERATE(as<std::size_t>{}, 0, 1, 2, 50, 2000, large_n);
  // Radii from "almost nobody" to "dozens of neighbours" in every dimension.
  const double radius = GENERATE(0.004, 0.03, 0.12);
  // Cells exactly as wide as the radius (the tight case) and wider (more candidates).
  const double width_factor = GENERATE(1.0, 1.7);
  // Targets are a prefix of the points: all of them, or half (the other half are only
  // neighbours, like ghost particles).
  const bool all_targets = GENERATE(true, false);
  const std::size_t targets = all_targets ? n : n / 2;
  // Cells of the search radius, or a half or a third of it searched (2 s + 1)^Dim deep.
  const int subdivisions = GENERATE(1, 2, 3);
  CAPTURE(Dim, n, radius, width_factor, targets, subdivisions);
  const auto pts = random_points<Dim>(n, static_cast<std::uint32_t>(1000 * Dim + n));
  // The brute-force answer depends on the points, the radius and the targets alone: found
  // once and kept while the generators vary the cells (n changes slowest, so the points'
  // answers are dropped when it does). Brute force on 5,000 points was most of this test.
  static std::map<std::tuple<std::size_t, double, std::size_t>, nb::NeighborList> references;
  if (!references.empty() && std::get<0>(references.begin()->first) != n) references.clear();
  const auto key = std::make_tuple(n, radius, targets);
  auto found = references.find(key);
  if (found == references.end()) {
    found = references.emplace(key, nb::brute_force_neighbors<Dim>(pts.coords(), targets, radius))
                .first;
  }
  const std::size_t entries = check_against_brute_force<Dim>(
      pts, targets, radius, width_factor * radius, subdivisions, &found->second);
  if (n >= 2000 && radius == 0.12 && targets == n) CHECK(entries > 0);
}

TEMPLATE_TEST_CASE_SIG("cell-list neighbours equal brute force on a lattice of the radius",
                       "[neighbors]", ((int Dim), Dim), 1, 2, 3) {
  // Spacing = radius puts every lattice pair at distance radius up to rounding, and each
  // point on a cell edge up to rounding: both implementations must make the same call on
  // every such pair, and the cell list must not lose one to binning. Spacing = radius / 2
  // adds pairs two cells edges apart.
  const double radius = GENERATE(0.013, 0.1, 0.7, 7.5 / 3.0);
  const double spacing = radius / GENERATE(1.0, 2.0);
  const double origin = GENERATE(0.0, -0.23, 1.234);
  const int per_side = Dim == 1 ? 2000 : (Dim == 2 ? 45 : 13);
  // Half-width cells put lattice points on cell edges at every half spacing too.
  const int subdivisions = GENERATE(1, 2);
  CAPTURE(Dim, radius, spacing, origin, subdivisions);
  const auto pts = lattice<Dim>(per_side, spacing, origin);
  const std::size_t entries =
      check_against_brute_force<Dim>(pts, pts.size(), radius, radius, subdivisions);
  if (spacing < radius) CHECK(entries > 0);
}

TEST_CASE("cell list finds a pair its binning puts two cells apart", "[neighbors]") {
  // Minimal lattice case: -0.23 + 6 * 0.7 and -0.23 + 7 * 0.7 are 0.6999999999999997
  // apart, inside the radius 0.7, yet in cells exactly 0.7 wide from the box origin -0.23
  // they bin to floor(5.9999...) = 5 and floor(7.0) = 7 by rounding, and the 3-cell
  // stencil of one misses the other.
  Points<1> pts;
  for (int i : {0, 6, 7}) pts.add({-0.23 + i * 0.7});
  const auto reference = nb::brute_force_neighbors<1>(pts.coords(), pts.size(), 0.7);
  REQUIRE(sorted_row(reference, 1) == std::vector<std::uint32_t>{2});
  const auto fast = cell_list_neighbors<1>(pts, pts.size(), 0.7, 0.7);
  CHECK(first_difference(fast, reference) == "");
}

TEMPLATE_TEST_CASE_SIG("pairs at exactly the radius are not neighbours", "[neighbors]",
                       ((int Dim), Dim), 1, 2, 3) {
  // Spacing 0.25 and all lattice coordinates are exact binary fractions, so axis pairs are
  // at exactly 0.25 and 0.5 with no rounding: the strict criterion decides, not luck.
  const int per_side = 6;
  const auto pts = lattice<Dim>(per_side, 0.25, 0.0);

  SECTION("radius equal to the spacing: nobody") {
    const auto fast = cell_list_neighbors<Dim>(pts, pts.size(), 0.25, 0.25);
    CHECK(fast.index.empty());
    CHECK(first_difference(fast, nb::brute_force_neighbors<Dim>(pts.coords(), pts.size(), 0.25)) ==
          "");
  }
  SECTION("radius twice the spacing: lattice offsets with |o|^2 < 4") {
    // Offsets in units of the spacing: 1D {+-1}: 2; 2D the 8 of the 3x3 block (the axis
    // points at 2 are exactly on the radius); 3D the 26 of the 3x3x3 block (max |o|^2 = 3).
    const std::size_t interior_count = Dim == 1 ? 2 : (Dim == 2 ? 8 : 26);
    const auto fast = cell_list_neighbors<Dim>(pts, pts.size(), 0.5, 0.5);
    // Point with lattice index 2 on every axis: two layers from every face.
    std::size_t interior = 0;
    for (int d = Dim - 1; d >= 0; --d) interior = interior * per_side + 2;
    CHECK(fast.row(interior).size() == interior_count);
    CHECK(first_difference(fast, nb::brute_force_neighbors<Dim>(pts.coords(), pts.size(), 0.5)) ==
          "");
  }
}

TEMPLATE_TEST_CASE_SIG("points on the upper edge of the bounding box", "[neighbors]",
                       ((int Dim), Dim), 1, 2, 3) {
  // With the box [0, 1] and width 0.25, (hi - lo) / width is exactly 4: the points at 1.0
  // are alone in the last cell row, the case an off-by-one in the cell count loses.
  // Width 0.3 and 0.1 do not divide the box (0.1 not even exactly).
  const double width = GENERATE(0.25, 0.3, 0.1);
  CAPTURE(Dim, width);
  auto pts = random_points<Dim>(400, 77 + Dim, 0.0, 1.0);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Points on each upper face, on the lower faces, and the two corners.
  for (int k = 0; k < 40; ++k) {
    std::array<double, Dim> p{};
    for (int d = 0; d < Dim; ++d) p[d] = u(gen);
    p[k % Dim] = k % 2 == 0 ? 1.0 : 0.0;
    pts.add(p);
  }
  std::array<double, Dim> corner{};
  pts.add(corner);
  corner.fill(1.0);
  pts.add(corner);
  // A near neighbour of the upper corner, so the corner's row is not trivially empty.
  corner.fill(1.0 - 0.4 * width / Dim);
  pts.add(corner);
  const std::size_t entries = check_against_brute_force<Dim>(pts, pts.size(), width, width);
  CHECK(entries > 0);
}

TEMPLATE_TEST_CASE_SIG("coincident points are neighbours of each other", "[neighbors]",
                       ((int Dim), Dim), 1, 2, 3) {
  auto pts = random_points<Dim>(200, 11 + Dim);
  // 10 copies of one point inside the box and 5 of one of the random points.
  std::array<double, Dim> p{};
  p.fill(0.1);
  const std::size_t first_copy = pts.size();
  for (int k = 0; k < 10; ++k) pts.add(p);
  const auto q = pts.at(3);
  for (int k = 0; k < 5; ++k) pts.add(q);
  const double radius = 0.05;
  check_against_brute_force<Dim>(pts, pts.size(), radius, radius);

  // Independent of the brute force: each copy lists the other nine and never itself.
  const auto fast = cell_list_neighbors<Dim>(pts, pts.size(), radius, radius);
  for (std::size_t i = first_copy; i < first_copy + 10; ++i) {
    CAPTURE(i);
    const auto row = sorted_row(fast, i);
    std::size_t copies = 0;
    for (std::uint32_t j : row) {
      if (j >= first_copy && j < first_copy + 10) ++copies;
    }
    CHECK(copies == 9);
    CHECK(!std::binary_search(row.begin(), row.end(), static_cast<std::uint32_t>(i)));
  }
}

TEMPLATE_TEST_CASE_SIG("clustered points with large empty regions", "[neighbors]", ((int Dim), Dim),
                       1, 2, 3) {
  // Four tight clusters at the corners of a box 20 radii wide: most cells are empty, and
  // rows of empty cells sit between occupied ones in the cell order.
  const double radius = 0.05;
  Points<Dim> pts;
  std::mt19937 gen(123 + Dim);
  std::uniform_real_distribution<double> u(0.0, 3.0 * radius);
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k < 100; ++k) {
      std::array<double, Dim> p{};
      for (int d = 0; d < Dim; ++d) p[d] = u(gen) + (((c >> (d % 2)) & 1) ? 20.0 * radius : 0.0);
      pts.add(p);
    }
  }
  for (std::size_t targets : {pts.size(), std::size_t{150}}) {
    CAPTURE(Dim, targets);
    CHECK(check_against_brute_force<Dim>(pts, targets, radius, radius) > 0);
  }
}

TEMPLATE_TEST_CASE_SIG("a far outlier widens the cells without losing neighbours", "[neighbors]",
                       ((int Dim), Dim), 1, 2, 3) {
  const double radius = 0.02;
  const double outlier = GENERATE(1e6, -1e6);
  CAPTURE(Dim, outlier);
  auto pts = random_points<Dim>(500, 31 + Dim);
  std::array<double, Dim> far{};
  far.fill(outlier);
  pts.add(far);

  nb::CellList<Dim> cells;
  cells.build(pts.coords(), radius);
  // The point of the case: the grid really was widened (1e6 / 0.02 cells per axis would
  // not fit), so the query stencil is much wider than the radius.
  CHECK(cells.cell_width() > radius);
  // Grid size follows the number of points, not the extent over the radius.
  CHECK(cells.cell_count() <= 100 * pts.size());
  // Targets include the outlier (all points) or stop short of it.
  CHECK(check_against_brute_force<Dim>(pts, pts.size(), radius, radius) > 0);
  check_against_brute_force<Dim>(pts, 250, radius, radius);
}

TEMPLATE_TEST_CASE_SIG("order() lists every point once, cell by cell in row-major order",
                       "[neighbors]", ((int Dim), Dim), 1, 2, 3) {
  const double width = 0.07;
  auto pts = random_points<Dim>(GENERATE(as<std::size_t>{}, 1, 50, 2000), 7 + Dim);
  const bool with_outlier = GENERATE(false, true);
  if (with_outlier) {
    // Widened cells must keep the same layout.
    std::array<double, Dim> far{};
    far.fill(1e6);
    pts.add(far);
  }
  const std::size_t n = pts.size();
  CAPTURE(Dim, n);
  nb::CellList<Dim> cells;
  cells.build(pts.coords(), width);
  REQUIRE(cells.point_count() == n);
  const auto order = cells.order();
  REQUIRE(order.size() == n);

  std::vector<int> seen(n, 0);
  for (std::uint32_t j : order) {
    REQUIRE(j < n);
    ++seen[j];
  }
  CHECK(std::count(seen.begin(), seen.end(), 1) == static_cast<std::ptrdiff_t>(n));

  // Recompute each point's cell from the box minimum and the reported width.
  const double w = cells.cell_width();
  CHECK(w >= width);
  std::array<double, Dim> lo{}, hi{};
  for (int d = 0; d < Dim; ++d) {
    lo[d] = *std::min_element(pts.x[d].begin(), pts.x[d].end());
    hi[d] = *std::max_element(pts.x[d].begin(), pts.x[d].end());
  }
  std::array<std::int64_t, Dim> per_axis{};
  std::size_t total = 1;
  for (int d = 0; d < Dim; ++d) {
    per_axis[d] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / w)) + 1;
    total *= static_cast<std::size_t>(per_axis[d]);
  }
  CHECK(cells.cell_count() == total);
  auto cell_of = [&](std::uint32_t i) {
    std::int64_t id = 0;
    for (int d = Dim - 1; d >= 0; --d) {
      const auto c = static_cast<std::int64_t>(std::floor((pts.x[d][i] - lo[d]) / w));
      id = id * per_axis[d] + c;
    }
    return id;
  };
  // Non-decreasing cell ids along order() means each cell is one contiguous run and the
  // runs come in increasing row-major (x fastest) order.
  std::size_t out_of_order = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (cell_of(order[k]) < cell_of(order[k - 1])) ++out_of_order;
  }
  CHECK(out_of_order == 0);
  // Not vacuous: with 2000 points in 0.07-wide cells the order is a real reordering, not
  // the identity. (With the outlier the widened cells may hold everything in one cell.)
  if (n >= 2000 && !with_outlier) {
    CHECK_FALSE(std::is_sorted(order.begin(), order.end()));
  }
}

TEMPLATE_TEST_CASE_SIG("for_each_candidate outside the bounding box", "[neighbors]",
                       ((int Dim), Dim), 1, 2, 3) {
  // The box [0, 0.99] is 9.9 cells wide, so the last cell ends at 1.0 and a query more
  // than 0.01 above the box lies in no cell at all: the stencil must still reach back.
  const double width = 0.1;
  const double top = 0.99;
  auto pts = random_points<Dim>(300, 17 + Dim, 0.0, top);
  // Points on the box faces at the middle of the other axes, so queries just outside have
  // something within reach.
  for (int d = 0; d < Dim; ++d) {
    std::array<double, Dim> p{};
    p.fill(0.5);
    p[d] = 0.0;
    pts.add(p);
    p[d] = top;
    pts.add(p);
  }
  // With subdivisions the cells are narrower and the stencil deeper: it must reach as far.
  // Not in 3D: 300 points in (0.99 / 0.05)^3 cells would make the cells widen for size.
  const int subdivisions = GENERATE(1, 2, 3);
  if (Dim == 3 && subdivisions > 1) return;
  CAPTURE(subdivisions);
  nb::CellList<Dim> cells;
  cells.build(pts.coords(), width, subdivisions);
  // Small set: the cells were not widened for size, so the reach is about `width`.
  REQUIRE(cells.search_radius() >= width);
  REQUIRE(cells.search_radius() < 1.01 * width);

  SECTION("far away: no candidates") {
    // 1e300 also checks that the cell coordinate is clamped before it becomes an integer.
    for (double offset : {1e3, -1e3, 1e300, -1e300}) {
      for (int d = 0; d < Dim; ++d) {
        std::array<double, Dim> q{};
        q.fill(0.5);
        q[d] = offset;
        CAPTURE(d, offset);
        CHECK(candidates_of<Dim>(cells, q).empty());
      }
    }
    std::array<double, Dim> q{};
    q.fill(std::numeric_limits<double>::quiet_NaN());
    CHECK(candidates_of<Dim>(cells, q).empty());
  }

  SECTION("just outside: every point within the cell width is a candidate") {
    for (double offset : {0.05, 0.3, 0.6, 0.95}) {
      for (int d = 0; d < Dim; ++d) {
        for (bool above : {false, true}) {
          std::array<double, Dim> q{};
          q.fill(0.5);
          q[d] = above ? top + offset * width : -offset * width;
          CAPTURE(d, offset, above);
          auto found = candidates_of<Dim>(cells, q);
          std::sort(found.begin(), found.end());
          CHECK(std::adjacent_find(found.begin(), found.end()) == found.end());
          std::size_t within = 0, missed = 0;
          for (std::uint32_t j = 0; j < pts.size(); ++j) {
            if (distance<Dim>(pts.at(j), q) < width) {
              ++within;
              if (!std::binary_search(found.begin(), found.end(), j)) ++missed;
            }
          }
          CHECK(within > 0);
          CHECK(missed == 0);
        }
      }
    }
  }
}

TEST_CASE("cell list and neighbour list reject bad input", "[neighbors]") {
  const auto pts = random_points<2>(20, 3);
  nb::CellList<2> cells;
  for (double bad :
       {0.0, -0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
        std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(cells.build(pts.coords(), bad), std::invalid_argument);
  }

  std::vector<double> x{0.0, 1.0, 2.0}, y{0.0, 1.0}, z{0.0, 1.0, 2.0};
  CHECK_THROWS_AS(cells.build(nb::Coordinates<2>{x, y}, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(cells.build(nb::Coordinates<2>{y, x}, 1.0), std::invalid_argument);
  nb::CellList<3> cells3;
  CHECK_THROWS_AS(cells3.build(nb::Coordinates<3>{x, z, y}, 1.0), std::invalid_argument);
  CHECK_NOTHROW(cells3.build(nb::Coordinates<3>{x, z, x}, 1.0));

  // A non-finite coordinate cannot be binned; it must not be silently put somewhere.
  std::vector<double> with_nan{0.0, std::numeric_limits<double>::quiet_NaN(), 2.0};
  CHECK_THROWS(cells.build(nb::Coordinates<2>{x, with_nan}, 1.0));
  // Finite points whose span overflows a double cannot be binned either (this once hung).
  nb::CellList<1> cells1;
  const std::vector<double> huge_span{-1e308, 1e308};
  CHECK_THROWS_AS(cells1.build(nb::Coordinates<1>{huge_span}, 1.0), std::domain_error);

  // The stencil of 3 cells per axis only covers a radius up to the cell width.
  // The cell width may exceed the requested 0.1 (by rounding margin or widening); the
  // limit is the width actually used.
  cells.build(pts.coords(), 0.1);
  const double width = cells.cell_width();
  REQUIRE(width >= 0.1);
  REQUIRE(width < 0.2);  // 20 points: not widened for size
  nb::NeighborList out;
  const double just_over = std::nextafter(width, 1.0);
  CHECK_THROWS_AS(nb::build_neighbor_list<2>(cells, pts.coords(), pts.size(), just_over, out),
                  std::invalid_argument);
  CHECK_THROWS_AS(nb::build_neighbor_list<2>(cells, pts.coords(), pts.size(), 1.0, out),
                  std::invalid_argument);
  CHECK_NOTHROW(nb::build_neighbor_list<2>(cells, pts.coords(), pts.size(), width, out));
  CHECK_NOTHROW(nb::build_neighbor_list<2>(cells, pts.coords(), pts.size(), 0.1, out));
  CHECK_THROWS_AS(nb::build_neighbor_list<2>(cells, pts.coords(), pts.size() + 1, 0.1, out),
                  std::invalid_argument);
}

TEMPLATE_TEST_CASE_SIG("neighbour list does not depend on the thread count", "[neighbors]",
                       ((int Dim), Dim), 1, 2, 3) {
  ThreadCountGuard guard;
  const auto pts = random_points<Dim>(large_n, 99 + Dim);
  const double radius = Dim == 1 ? 0.002 : (Dim == 2 ? 0.02 : 0.07);
  // All targets, and a count above the threshold that does not split evenly over threads.
  const std::size_t targets = GENERATE(true, false) ? large_n : large_n - 1337;
  CAPTURE(Dim, targets);
  nb::CellList<Dim> cells;
  cells.build(pts.coords(), radius);

  std::vector<nb::NeighborList> lists;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    nb::NeighborList out;
    nb::build_neighbor_list<Dim>(cells, pts.coords(), targets, radius, out);
    lists.push_back(std::move(out));
  }
  REQUIRE_FALSE(lists[0].index.empty());
  for (std::size_t k = 1; k < lists.size(); ++k) {
    CAPTURE(k);
    // Exact equality, order inside rows included: the solver's sums run in row order, so a
    // thread-dependent order would make results depend on the thread count.
    CHECK(lists[k].offsets == lists[0].offsets);
    CHECK(lists[k].index == lists[0].index);
  }
}

namespace {

// Rows of the per-point-radius rule by brute force: j is a neighbour of target i when
// |x_i - x_j| < max(r_i, r_j); sorted by index.
nb::NeighborList brute_force_with_radii(const Points<2>& pts, const std::vector<double>& radii,
                                        std::size_t targets) {
  nb::NeighborList out;
  out.offsets.push_back(0);
  for (std::size_t i = 0; i < targets; ++i) {
    for (std::size_t j = 0; j < pts.size(); ++j) {
      const double dx = pts.x[0][j] - pts.x[0][i], dy = pts.x[1][j] - pts.x[1][i];
      if (j != i && dx * dx + dy * dy < std::max(radii[i] * radii[i], radii[j] * radii[j]))
        out.index.push_back(static_cast<std::uint32_t>(j));
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.index.size()));
  }
  return out;
}

// Radii as a flow has them: most near `typical`, one in eight up to 3x, one in a hundred up
// to 10x, a few zero.
std::vector<double> spread_radii(std::size_t n, double typical, std::uint32_t seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> radii(n);
  for (double& r : radii) {
    const double pick = u(gen);
    r = pick < 0.01    ? 0.0
        : pick < 0.02  ? typical * (1.0 + 9.0 * u(gen))
        : pick < 0.145 ? typical * (1.0 + 2.0 * u(gen))
                       : typical * (0.8 + 0.4 * u(gen));
  }
  return radii;
}

}  // namespace

TEST_CASE("neighbours of points with their own radii equal brute force, whatever the cells",
          "[neighbors]") {
  const std::size_t n = GENERATE(as<std::size_t>{}, 1, 300, large_n);
  const double typical = 0.02;
  // Cells for the typical radius (wider radii take the builder's other ways), for half of it
  // (every radius is "wide") and for the largest (none is).
  const double cell_radius = GENERATE(0.02, 0.01, 0.2);
  const int subdivisions = GENERATE(1, 2);
  const bool all_targets = GENERATE(true, false);
  const std::size_t targets = all_targets ? n : n / 2;
  CAPTURE(n, cell_radius, subdivisions, targets);
  const auto pts = random_points<2>(n, static_cast<std::uint32_t>(77 + n));
  const auto radii = spread_radii(n, typical, static_cast<std::uint32_t>(5 + n));
  nb::CellList<2> cells;
  cells.build(pts.coords(), cell_radius, subdivisions);
  nb::NeighborList fast;
  nb::build_neighbor_list<2>(cells, pts.coords(), radii, targets, fast);
  const auto reference = brute_force_with_radii(pts, radii, targets);
  REQUIRE(fast.row_count() == targets);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < targets; ++i)
    mismatches += sorted_row(fast, i) != sorted_row(reference, i);
  CHECK(mismatches == 0);
  CHECK(fast.index.size() == reference.index.size());
  if (n == large_n) CHECK(reference.index.size() > 10 * targets);  // the test has pairs to lose
}

TEST_CASE("neighbours of points with their own radii do not depend on the thread count",
          "[neighbors]") {
  ThreadCountGuard guard;
  const auto pts = random_points<2>(large_n, 4242);
  const auto radii = spread_radii(large_n, 0.02, 17);
  nb::CellList<2> cells;
  cells.build(pts.coords(), 0.02, 2);
  std::vector<nb::NeighborList> lists;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    nb::NeighborList out;
    nb::build_neighbor_list<2>(cells, pts.coords(), radii, large_n - 1337, out);
    lists.push_back(std::move(out));
  }
  REQUIRE_FALSE(lists[0].index.empty());
  for (std::size_t k = 1; k < lists.size(); ++k) {
    CHECK(lists[k].offsets == lists[0].offsets);
    CHECK(lists[k].index == lists[0].index);
  }
}

TEST_CASE("rows of points with their own radii are in ascending order", "[neighbors]") {
  const auto pts = random_points<2>(large_n, 9);
  const auto radii = spread_radii(large_n, 0.02, 10);
  nb::CellList<2> cells;
  cells.build(pts.coords(), 0.02, 2);
  nb::NeighborList list;
  nb::build_neighbor_list<2>(cells, pts.coords(), radii, large_n, list);
  std::size_t unsorted = 0;
  for (std::size_t i = 0; i < large_n; ++i) {
    const auto row = list.row(i);
    unsorted += std::is_sorted(row.begin(), row.end()) ? 0 : 1;
  }
  CHECK(unsorted == 0);
  CHECK(list.index.size() > 10 * large_n);
}

// A few points moved, widened or appended, as a depth sum and splitting change them; the
// repaired rows must be the rows a new search gives, entry for entry.
TEST_CASE("rows repaired around a few changed points equal a new search", "[neighbors]") {
  const std::size_t n = GENERATE(as<std::size_t>{}, 300, large_n);
  // Targets appended (as splitting adds daughters), or candidates that are not targets (as
  // ghosts are), or neither. Not both: the old list's candidates-only points would move.
  const auto [appended, candidates_only] =
      GENERATE(table<std::size_t, std::size_t>({{0, 0}, {7, 0}, {0, 40}}));
  CAPTURE(n, appended, candidates_only);
  const std::size_t targets_before = n - candidates_only;
  auto pts = random_points<2>(n, static_cast<std::uint32_t>(3 + n));
  auto radii = spread_radii(n, 0.02, static_cast<std::uint32_t>(4 + n));
  nb::CellList<2> cells;
  cells.build(pts.coords(), 0.02, 2);
  nb::NeighborList list;
  nb::build_neighbor_list<2>(cells, pts.coords(), radii, targets_before, list);
  const nb::NeighborList before = list;

  // Targets appended go before the candidates-only points, as fluid particles precede ghosts.
  Points<2> now;
  std::vector<double> now_radii;
  for (std::size_t i = 0; i < targets_before; ++i) {
    now.add(pts.at(i));
    now_radii.push_back(radii[i]);
  }
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::uint32_t> changed;
  for (std::size_t k = 0; k < appended; ++k) {
    now.add({u(gen) - 0.37, u(gen) - 0.37});
    now_radii.push_back(0.02 * (0.5 + 2.0 * u(gen)));
  }
  for (std::size_t i = targets_before; i < n; ++i) {
    now.add(pts.at(i));
    now_radii.push_back(radii[i]);
  }
  for (std::size_t i = 0; i < now.size(); i += 37) {
    if (i >= targets_before && i < targets_before + appended) continue;
    if (i % 2 == 0) {
      now.x[0][i] += 0.01 * (u(gen) - 0.5);  // moved
    } else {
      now_radii[i] *= 1.0 + 0.3 * u(gen);  // widened
    }
    changed.push_back(static_cast<std::uint32_t>(i));
  }
  for (std::size_t k = 0; k < appended; ++k)
    changed.push_back(static_cast<std::uint32_t>(targets_before + k));
  std::sort(changed.begin(), changed.end());
  const std::size_t targets = targets_before + appended;

  nb::CellList<2> now_cells;
  now_cells.build(now.coords(), 0.02, 2);
  const auto rewritten =
      nb::repair_rows<2>(now_cells, now.coords(), now_radii, targets, changed, list);
  nb::NeighborList fresh;
  nb::build_neighbor_list<2>(now_cells, now.coords(), now_radii, targets, fresh);
  CHECK(list.offsets == fresh.offsets);
  CHECK(list.index == fresh.index);

  // Every row that differs from the old one is among those said rewritten, and so is every
  // changed target.
  std::size_t unreported = 0;
  for (std::size_t i = 0; i < targets; ++i) {
    const bool differs =
        i >= before.row_count() || !std::ranges::equal(before.row(i), fresh.row(i));
    const bool said = std::binary_search(rewritten.begin(), rewritten.end(), i);
    unreported += differs && !said ? 1 : 0;
  }
  CHECK(unreported == 0);
  for (const std::uint32_t c : changed)
    if (c < targets) CHECK(std::binary_search(rewritten.begin(), rewritten.end(), c));
  CHECK(rewritten.size() < targets / 2 + 50);  // a repair, not a rewrite of everything
}

TEST_CASE("a repair refuses changes it cannot trust", "[neighbors]") {
  const auto pts = random_points<2>(50, 1);
  const std::vector<double> radii(50, 0.1);
  nb::CellList<2> cells;
  cells.build(pts.coords(), 0.1);
  nb::NeighborList list;
  nb::build_neighbor_list<2>(cells, pts.coords(), radii, 40, list);
  const std::vector<std::uint32_t> unsorted{5, 3}, beyond{60};
  CHECK_THROWS_AS(nb::repair_rows<2>(cells, pts.coords(), radii, 40, unsorted, list),
                  std::invalid_argument);
  CHECK_THROWS_AS(nb::repair_rows<2>(cells, pts.coords(), radii, 40, beyond, list),
                  std::invalid_argument);
  // A new target that is not listed as changed has no row to keep.
  CHECK_THROWS_AS(nb::repair_rows<2>(cells, pts.coords(), radii, 45, {}, list),
                  std::invalid_argument);
}
