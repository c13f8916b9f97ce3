#pragma once
// Dynamic particle splitting (method.md section 1, eqs 10-12 and appendix A).
//
// Where water thins, particles drift apart and the depth a particle can represent is
// bounded below by its own volume (docs/verification.md, "the tip"). A particle whose area
// has grown past `area_ratio_threshold` times its reference area A_0 is split in two along an
// eigenvector t_i of the moment matrix C_i = sum_j w_ij x_ij x_ij^T (appendix A), the daughters
// placed at x_i +- (alpha_s l_i / 2) t_i (eq 10).
//
// Which eigenvector: appendix A prints the one of the larger eigenvalue ("split along the
// direction in which the neighbours spread"). Measured on both seed cases (docs/splitting.md),
// that axis lies along a front: a front particle has neighbours beside it and none ahead, and
// r^2 w(r) peaks at r = 0.8 r_e, so neighbours that have drifted far away weigh less, not more.
// Splitting along the front crowds the front row and never thins the tip. The smaller
// eigenvalue's axis points into the gap the particles left, which is what the paper's figure 8
// shows (the spacing along the flow kept), and it is the default; the printed rule stays
// available as SplitAxis::major. Each daughter takes the depth eq 12 gives at its position times
// half the parent's area as its volume, so the two volumes add up to the parent's exactly; their
// velocities are eq 12's, shifted by one common amount so that momentum is conserved exactly too.
// Daughters keep the parent's A_0: it is the resolution the scene asked for, and halving it would
// make every daughter split again at once.
//
// A particle whose area has reached the scheme's radius cap (swe::Settings::area_ratio_cap()) is
// not split. Its radius no longer follows its area, so its area is the kernel's, not the water's:
// a lone particle has A = 1 / w(0) at the capped radius whatever its volume (30 A_0 with the
// defaults), and each daughter, half as large, lands as alone as its parent and splits again.
//
// Nor is a particle whose water, spread over A_0, is thinner than `min_depth_m`. Splitting keeps
// a thinning sheet at the scene's resolution by giving each particle the volume its depth fills
// A_0 with: a particle of volume V stands for water V / A_0 deep at full resolution. Below the
// floor the sheet is thinner than the scene resolves, and is left to coarsen: its particles keep
// their volume and spread. Without a floor a film running down a dry slope is split generation
// after generation (docs/splitting.md, "Films and lone particles"), its particles shrinking to
// 1e-10 of their first volume while the time step follows them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "swemps/boundaries/ghost_walls.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::splitting {

// The axis of C_i along which daughters are placed.
enum class SplitAxis {
  minor,  // eigenvector of the smaller eigenvalue: into the gap (default)
  major,  // eigenvector of the larger eigenvalue: appendix A as printed
};

struct SplittingSettings {
  double area_ratio_threshold = 1.5;  // split when A > threshold A_0
  double alpha_s = 0.7;               // daughter separation, in particle sizes l = sqrt(A) (eq 10)
  std::size_t max_particles = 0;      // no split beyond this many particles; 0 = no cap
  // No split of a particle whose volume over A_0 is below this depth (see above); 0: no floor.
  double min_depth_m = 1e-5;
  // The area ratio A/A_0 at which the scheme's radius stops growing; a particle at or past it is
  // not split (see above). Set from the numerics when the scene is built; 0: no such rule.
  double radius_cap_area_ratio = 0.0;
  SplitAxis axis = SplitAxis::minor;
};

// Symmetric 2x2 moment matrix of appendix A.
struct MomentMatrix {
  double xx = 0.0, xy = 0.0, yy = 0.0;
};

MomentMatrix moment_matrix(const particles::SweParticles& p, const neighbors::NeighborList& nl,
                           const swe::ParticleKernel& w, std::size_t i);

// Unit eigenvector of C for the chosen axis: the larger eigenvalue (eq 11 / appendix A) or the
// smaller one. For an isotropic C every direction qualifies; x (major) and y (minor) are
// returned so the choice is reproducible.
std::array<double, 2> split_direction(const MomentMatrix& c, SplitAxis axis);

class ParticleSplitting final : public swe::Effect {
 public:
  ParticleSplitting(SplittingSettings settings, std::vector<boundaries::WallSegment> walls);

  std::string_view name() const override { return "particle splitting"; }
  swe::Stage stage() const override { return swe::Stage::resolution; }
  void apply(swe::StepContext& context) override;
  bool lists_changes() const override { return true; }  // each parent it splits
  std::string report() const override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;

  std::size_t splits() const { return splits_; }
  std::size_t refused_at_walls() const { return refused_at_walls_; }
  std::size_t refused_at_cap() const { return refused_at_cap_; }

 private:
  struct Daughter {
    double x, y, u, v, volume, depth;
  };
  struct Plan {
    std::size_t parent;
    Daughter a, b;
    double area;  // each daughter's area until the next summation: half the parent's
  };
  bool crosses_wall(double x0, double y0, double x1, double y1) const;
  bool plan_split(const swe::StepContext& context, std::size_t i, Plan& plan) const;

  SplittingSettings settings_;
  boundaries::WallIndex walls_;
  std::vector<Plan> plans_;
  std::vector<std::uint8_t> oversized_;  // per particle: area past the threshold (apply)
  std::size_t splits_ = 0, refused_at_walls_ = 0, refused_at_cap_ = 0;
};

}  // namespace swemps::splitting
