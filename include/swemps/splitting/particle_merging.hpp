#pragma once
// Particle merging: the converse of splitting, where water gathers.
//
// Where water deepens (a pond filling, the water behind a bore, a shore the sea climbs), the
// particles' areas A = V / h shrink below the reference area A_0 the scene asked for, and the
// run spends its time on more particles than the resolution needs. A particle whose area has
// fallen below `area_ratio_threshold` times its A_0 is merged with a neighbour, as Vacondio,
// Rogers, Stansby & Mignosa (2013, "Shallow water SPH for flooding with dynamic particle coalescing
// and splitting") coalesce particles whose mass has fallen below a threshold. The merged particle
// takes
//   V = V_a + V_b,   x = (V_a x_a + V_b x_b) / V,   u = (V_a u_a + V_b u_b) / V,
// so volume and momentum are conserved (to the rounding of one sum) and its position is the
// pair's centre of volume; its area until the next summation is A_a + A_b, its radius
// sqrt(H_a^2 + H_b^2) (the radius of that area for a radius kappa sqrt(A)), its A_0 the mean
// of the pair's.
//
// A particle below the threshold (a candidate) takes the nearest particle within the reach of
// either kernel (a tiny particle beside particles of full size lies within theirs) whose
// merge keeps the pair's area below the threshold times their reference areas together:
// A_a + A_b < threshold (A_0a + A_0b). Two candidates always qualify; a candidate and a
// particle of full size do only where the candidate is small enough to make up the
// difference. A merged particle's area is thus below twice the threshold times its A_0, and
// the scene refuses a threshold of half the splitting threshold or more, which would merge
// particles that splitting splits again at once. The kinetic energy of the pair's relative
// motion is lost in a merge (an inelastic collision); at rest there is none.
//
// It acts in the topology stage, after the move, as the other effects that remove particles
// do, so that the refresh that follows every step already sums the new set: merging adds no
// second neighbour search. It finds partners itself, on a cell list it builds only in steps
// that have candidates.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/neighbors/cell_list.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::splitting {

struct MergingSettings {
  double area_ratio_threshold = 0.5;  // merge when A < threshold A_0
};

class ParticleMerging final : public swe::Effect {
 public:
  ParticleMerging(MergingSettings settings, std::vector<boundaries::WallSegment> walls);

  std::string_view name() const override { return "particle merging"; }
  swe::Stage stage() const override { return swe::Stage::topology; }
  void apply(swe::StepContext& context) override;
  std::string report() const override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;

  std::size_t merges() const { return merges_; }

 private:
  bool merge_allowed(const particles::SweParticles& p, std::size_t i, std::size_t j) const;
  // The untaken particle nearest to candidate i that it may merge with, within the reach of
  // either kernel and on its side of every wall; i itself if there is none.
  std::size_t nearest_partner(const particles::SweParticles& p, std::size_t i) const;

  MergingSettings settings_;
  boundaries::WallIndex walls_;
  // Per step: the candidates' particle indices (ascending); per particle, whether it is taken
  // and whether it was merged away.
  std::vector<std::uint32_t> candidates_;
  std::vector<std::uint8_t> taken_, merged_away_;
  neighbors::CellList<2> cells_;
  std::size_t merges_ = 0;
};

}  // namespace swemps::splitting
