#pragma once
// Thacker's planar surface in a paraboloid (SWASHES 2D, Delestre et al. 2013, section 4.2.2):
// a bowl z(r) = -h0 (1 - r^2 / a^2) around (cx, cy) holds water whose surface is a plane that
// rotates around the bowl without changing shape, wetting and drying its sides, with period
// T = 2 pi / omega, omega = sqrt(2 g h0) / a. Frictionless; the velocity is uniform:
//   h(x, y, t) = max(0, eta h0 / a^2 (2 (x - cx) cos(omega t) + 2 (y - cy) sin(omega t) - eta)
//                       - z(x, y)),
//   u = -eta omega sin(omega t),  v = eta omega cos(omega t).
// eta is a length (it enters with x, and u = -eta omega sin): h = h0 / a^2 (a^2 - |x - c(t)|^2)
// with c(t) = (cx + eta cos(omega t), cy + eta sin(omega t)), a cap of the bowl's own shape on
// a disc of radius a around c(t). So the water's centre of mass is c(t), going round at radius
// eta.

namespace swemps::verification {

struct ThackerProblem {
  double bowl_radius_m = 1.0;  // a
  double depth_m = 0.1;        // h0, the bowl's depth at its centre
  double eta_m = 0.5;          // eta: how far the water's centre is off the bowl's
  double centre_x_m = 2.0, centre_y_m = 2.0;
  double gravity_m_s2 = 9.81;
};

double thacker_omega(const ThackerProblem& problem);
double thacker_bed(const ThackerProblem& problem, double x_m, double y_m);
double thacker_depth(const ThackerProblem& problem, double x_m, double y_m, double t_s);
// The uniform velocity at time t.
void thacker_velocity(const ThackerProblem& problem, double t_s, double& u_m_s, double& v_m_s);
// The water's centre of mass at time t.
void thacker_centroid(const ThackerProblem& problem, double t_s, double& x_m, double& y_m);

}  // namespace swemps::verification
