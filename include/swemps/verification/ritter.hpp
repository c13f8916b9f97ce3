#pragma once
// Ritter's dam break on a dry, flat, frictionless bed (method.md eq 14) and the error
// measures swe-mps is verified with.

#include <cstddef>
#include <vector>

#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/operators.hpp"

namespace swemps::verification {

struct RitterProblem {
  double dam_x_m;          // x_dam
  double initial_depth_m;  // h0
  double gravity_m_s2;
  double reservoir_start_x_m = 0.0;  // back wall; the solution holds until the wave reaches it
};

// eq 14 (and the undisturbed reservoir / dry bed outside the fan), t > 0.
double ritter_depth(const RitterProblem& problem, double x_m, double t_s);
double ritter_velocity(const RitterProblem& problem, double x_m, double t_s);

// A depth profile h(x) on uniformly spaced x (e.g. a grid row averaged across y).
struct Profile {
  double x0_m, dx_m;
  std::vector<double> depth_m;
};

// The rectangle a channel profile is taken over, in m.
struct Channel {
  double x_min_m, x_max_m, y_min_m, y_max_m;
};

// The depth along a channel: eq 7 evaluated at the cell centres of a grid of square cells of
// side dx_m covering the channel, averaged across it (y). A grid finer than the particles
// (dx = spacing / 4 in the verification) samples the summed depth between them too.
Profile channel_profile(const particles::SweParticles& p, const swe::ParticleKernel& kernel,
                        const Channel& channel, double dx_m);

struct RitterErrors {
  double fan_l1;    // (1/L) integral over the fan of |h - h_R| dx, / h0
  double fan_l2;    // sqrt((1/L) integral (h - h_R)^2 dx) / h0
  double fan_linf;  // max |h - h_R| over the fan / h0
  // L1 as fan_l1 over the upstream half of the fan, x_dam - t sqrt(g h0) <= x <= x_dam,
  // where the exact depth stays above 4/9 h0 and so above the depth a row of unsplit
  // particles can represent (docs/verification.md).
  double upstream_fan_l1;
  double front_x_m;        // largest x with h > front_threshold
  double exact_front_x_m;  // x_dam + 2 t sqrt(g h0)
};

// Fan: x_dam - t sqrt(g h0) <= x <= x_dam + 2 t sqrt(g h0).
RitterErrors compare_with_ritter(const RitterProblem& problem, const Profile& profile, double t_s,
                                 double front_threshold_m = 1e-3);

}  // namespace swemps::verification
