#include "swemps/verification/thacker.hpp"

#include <algorithm>
#include <cmath>

namespace swemps::verification {

double thacker_omega(const ThackerProblem& problem) {
  return std::sqrt(2.0 * problem.gravity_m_s2 * problem.depth_m) / problem.bowl_radius_m;
}

double thacker_bed(const ThackerProblem& problem, double x_m, double y_m) {
  const double dx = x_m - problem.centre_x_m, dy = y_m - problem.centre_y_m;
  const double a2 = problem.bowl_radius_m * problem.bowl_radius_m;
  return -problem.depth_m * (1.0 - (dx * dx + dy * dy) / a2);
}

double thacker_depth(const ThackerProblem& problem, double x_m, double y_m, double t_s) {
  const double phase = thacker_omega(problem) * t_s;
  const double dx = x_m - problem.centre_x_m, dy = y_m - problem.centre_y_m;
  const double a2 = problem.bowl_radius_m * problem.bowl_radius_m;
  const double surface =
      problem.eta_m * problem.depth_m / a2 *
      (2.0 * dx * std::cos(phase) + 2.0 * dy * std::sin(phase) - problem.eta_m);
  return std::max(0.0, surface - thacker_bed(problem, x_m, y_m));
}

void thacker_velocity(const ThackerProblem& problem, double t_s, double& u_m_s, double& v_m_s) {
  const double omega = thacker_omega(problem);
  u_m_s = -problem.eta_m * omega * std::sin(omega * t_s);
  v_m_s = problem.eta_m * omega * std::cos(omega * t_s);
}

void thacker_centroid(const ThackerProblem& problem, double t_s, double& x_m, double& y_m) {
  const double phase = thacker_omega(problem) * t_s;
  x_m = problem.centre_x_m + problem.eta_m * std::cos(phase);
  y_m = problem.centre_y_m + problem.eta_m * std::sin(phase);
}

}  // namespace swemps::verification
