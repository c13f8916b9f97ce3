// Pathlines (docs/provenance.md, "Pathlines"): the particles carry their line through sorts,
// splits, merges and removal; the choice of particles, the recorder's vertices and its record
// for checkpoints.

#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

#include "swemps/maps/pathlines.hpp"
#include "swemps/particles/swe_particles.hpp"
#include "swemps/terrain/footprints.hpp"

using swemps::maps::choose_pathline_particles;
using swemps::maps::Pathline;
using swemps::maps::PathlineChoice;
using swemps::maps::PathlineRecorder;
using swemps::particles::kNoPathline;
using swemps::particles::Origin;
using swemps::particles::PathlineEnd;
using swemps::particles::SweParticles;

namespace {

// A row of `n` particles 1 m apart along x, each of 1 m3.
SweParticles row(std::size_t n, bool pathlines = true, std::size_t labels = 0) {
  SweParticles p;
  p.track_provenance(labels, false);
  if (pathlines) p.track_pathlines();
  for (std::size_t i = 0; i < n; ++i) {
    const Origin origin{labels > 0 ? static_cast<std::uint32_t>(i % labels) : 0u, 0.0};
    p.add_fluid(static_cast<double>(i), 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, origin);
  }
  return p;
}

}  // namespace

TEST_CASE("particles carry their pathline through sorts, merges and removal", "[pathlines]") {
  SweParticles p = row(5);
  REQUIRE(p.pathline == std::vector<std::int32_t>(5, kNoPathline));
  p.pathline[1] = 0;
  p.pathline[3] = 1;
  p.pathline[4] = 2;

  const std::vector<std::uint32_t> order{4, 3, 2, 1, 0};
  p.reorder(order);
  CHECK(p.pathline == std::vector<std::int32_t>{2, 1, kNoPathline, 0, kNoPathline});
  CHECK(p.x[3] == 1.0);

  // Particle 4 (untracked) takes in particle 3 (line 0): the line goes on with particle 4.
  p.hand_over_pathline(3, 4);
  CHECK(p.pathline[4] == 0);
  CHECK(p.pathline[3] == kNoPathline);
  // Particle 1 (line 1) takes in particle 0 (line 2): both are followed, so line 2 ends
  // there, where particle 0 was, joining line 1; removing particle 0 ends nothing more.
  p.hand_over_pathline(0, 1);
  CHECK(p.pathline[1] == 1);
  CHECK(p.pathline[0] == kNoPathline);
  REQUIRE(p.pathline_ends.size() == 1);
  CHECK(p.pathline_ends[0].pathline == 2);
  CHECK(p.pathline_ends[0].x == 4.0);
  CHECK(p.pathline_ends[0].cause == PathlineEnd::Cause::merged);
  CHECK(p.pathline_ends[0].into == 1);
  const std::vector<std::uint8_t> merged{1, 0, 0, 1, 0};
  p.remove(merged);
  CHECK(p.pathline == std::vector<std::int32_t>{1, kNoPathline, 0});
  REQUIRE(p.pathline_ends.size() == 1);

  // Leaving the domain.
  const std::vector<std::uint8_t> gone{0, 0, 1};
  p.remove(gone);
  REQUIRE(p.pathline_ends.size() == 2);
  CHECK(p.pathline_ends[1].pathline == 0);
  CHECK(p.pathline_ends[1].x == 0.0);
  CHECK(p.pathline_ends[1].cause == PathlineEnd::Cause::left);

  // A new particle (a split's second daughter, an inflow's) carries none.
  p.add_fluid(9.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0);
  CHECK(p.pathline.back() == kNoPathline);
}

TEST_CASE("particles that follow no pathline carry no index", "[pathlines]") {
  SweParticles p = row(4, false);
  CHECK(p.pathline.empty());
  p.hand_over_pathline(0, 1);  // nothing to hand over
  const std::vector<std::uint8_t> gone{1, 0, 0, 0};
  p.remove(gone);
  CHECK(p.pathline.empty());
  CHECK(p.pathline_ends.empty());
  CHECK_THROWS_AS(p.track_pathlines(), std::logic_error);  // only before the first particle
}

TEST_CASE("the particles chosen pass every filter, spread evenly over the rest", "[pathlines]") {
  const SweParticles p = row(100, true, 2);  // labels 0, 1, 0, 1, ...
  PathlineChoice all;
  all.count = 1000;
  CHECK(choose_pathline_particles(p, all).size() == 100);

  PathlineChoice ten;
  ten.count = 10;
  const auto spread = choose_pathline_particles(p, ten);
  REQUIRE(spread.size() == 10);
  for (std::size_t k = 0; k < 10; ++k) CHECK(spread[k] == 10 * k);

  // Inside x in (19.5, 40.5) and of label 1: the odd ones from 21 to 39.
  const swemps::terrain::Footprints area(
      {{{{19.5, -1.0}, {40.5, -1.0}, {40.5, 1.0}, {19.5, 1.0}}, {}}});
  PathlineChoice odd;
  odd.count = 100;
  odd.label = 1;
  odd.area = &area;
  const auto chosen = choose_pathline_particles(p, odd);
  REQUIRE(chosen.size() == 10);
  CHECK(chosen.front() == 21);
  CHECK(chosen.back() == 39);
  for (const auto i : chosen) CHECK(i % 2 == 1);

  PathlineChoice unknown;
  unknown.label = 2;
  CHECK_THROWS_AS(choose_pathline_particles(p, unknown), std::invalid_argument);
}

TEST_CASE("the recorder keeps a vertex per time, ends lines, and restores its record",
          "[pathlines]") {
  SweParticles p = row(6, true, 3);
  PathlineRecorder recorder;
  const std::vector<std::uint32_t> chosen{1, 4};
  recorder.start(p, chosen, 2.0);
  p.pathline[1] = 0;
  p.pathline[4] = 1;
  REQUIRE(recorder.lines().size() == 2);
  CHECK(recorder.lines()[1].label == 1u);  // particle 4's water is label 1's

  for (std::size_t i = 0; i < p.fluid_count(); ++i) p.x[i] += 0.5;
  recorder.record(p, 3.0);
  recorder.record(p, 3.0);  // once a time
  recorder.record(p, 2.5);  // never back in time
  CHECK(recorder.lines()[0].t == std::vector<double>{2.0, 3.0});
  CHECK(recorder.lines()[0].x == std::vector<double>{1.0, 1.5});

  const std::vector<PathlineEnd> ends{{1, 4.75, 0.25, PathlineEnd::Cause::left, -1}};
  recorder.end(ends, 3.25);
  p.pathline[4] = kNoPathline;
  recorder.record(p, 4.0);
  const Pathline& ended = recorder.lines()[1];
  CHECK(ended.fate == Pathline::Fate::left);
  CHECK(ended.t == std::vector<double>{2.0, 3.0, 3.25});
  CHECK(ended.y.back() == 0.25);
  CHECK_FALSE(ended.merged_into);
  CHECK(recorder.lines()[0].t.size() == 3);
  CHECK(recorder.vertices() == 6);

  // Line 0's particle merges into another followed one (the recorder takes the join as given).
  const std::vector<PathlineEnd> joined{{0, 2.0, 0.0, PathlineEnd::Cause::merged, 1}};
  recorder.end(joined, 4.5);
  CHECK(recorder.lines()[0].fate == Pathline::Fate::merged);
  CHECK(recorder.lines()[0].merged_into == 1u);

  PathlineRecorder restored;
  restored.restore(recorder.state());
  CHECK(restored.started());
  CHECK(restored.state() == recorder.state());
  CHECK(restored.lines()[1].fate == Pathline::Fate::left);
  CHECK(restored.lines()[0].merged_into == 1u);
  CHECK(restored.lines()[0].label == 1u);  // particle 1's water: label 1

  auto damaged = recorder.state();
  damaged.pop_back();
  CHECK_THROWS_AS(restored.restore(damaged), std::invalid_argument);
  damaged = recorder.state();
  damaged.push_back(0.0);
  CHECK_THROWS_AS(restored.restore(damaged), std::invalid_argument);
}
