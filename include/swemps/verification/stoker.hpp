#pragma once
// Stoker's dam break on a wet, flat, frictionless bed: still water h_l upstream of the dam
// and h_r < h_l downstream. A rarefaction runs upstream as in Ritter's solution (eq 14), a
// shock (bore) runs downstream, and between them lies a uniform state (h_m, u_m). The shock
// is what makes it hard for particle codes: the exact solution jumps from h_r to h_m.

#include "swemps/verification/ritter.hpp"

namespace swemps::verification {

struct StokerProblem {
  double dam_x_m;
  double upstream_depth_m;    // h_l
  double downstream_depth_m;  // h_r, 0 < h_r < h_l
  double gravity_m_s2;
};

// The state between the rarefaction and the shock, and the shock's speed. h_m solves
//   2 (sqrt(g h_l) - sqrt(g h_m)) = (h_m - h_r) sqrt(g (h_m + h_r) / (2 h_m h_r)),
// the rarefaction's Riemann invariant on the left equal to the shock's jump condition on the
// right; the shock runs at S = h_m u_m / (h_m - h_r) (mass conservation across it).
struct StokerState {
  double middle_depth_m;
  double middle_velocity_m_s;
  double shock_speed_m_s;
};
StokerState stoker_state(const StokerProblem& problem);

double stoker_depth(const StokerProblem& problem, double x_m, double t_s);
double stoker_velocity(const StokerProblem& problem, double x_m, double t_s);

struct StokerErrors {
  // (1/L) integral |h - h_S| dx / h_l over the disturbed region, from the rarefaction's head
  // to one spacing of the profile past the exact shock.
  double l1;
  double linf;  // max |h - h_S| / h_l over the same region
  // Largest depth over the middle state's plateau, away from the shock by 10 % of the
  // plateau's length on each side, relative to h_m: the overshoot of an oscillating shock.
  double plateau_overshoot;
  double shock_x_m;        // where the profile first falls below (h_m + h_r) / 2, past the dam
  double exact_shock_x_m;  // dam + S t
};
StokerErrors compare_with_stoker(const StokerProblem& problem, const Profile& profile, double t_s);

}  // namespace swemps::verification
