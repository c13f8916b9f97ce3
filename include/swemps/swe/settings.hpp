#pragma once
// Numerical settings of the shallow-water solver: plain values, no file formats.

#include <optional>

namespace swemps::swe {

// How depth is summed and which force the water surface exerts (swe/scheme.hpp).
enum class SchemeKind {
  // Saigo & Koshizuka's eqs 5-9: the spiky kernel with one radius for all (eq 9), the depth
  // by eq 7, the flow driven by the gradient variant below.
  seed,
  // A radius per particle, h_i = kappa sqrt(A_i), found with its depth by Newton iteration;
  // the force that follows from the summed depth (grad-h terms included), equal and opposite
  // in every pair; dissipation on approaching pairs only (docs/method.md).
  conservative,
};

// The kernel shape of the conservative scheme (kernels module).
enum class KernelShape { cubic_spline, spiky, wendland_c2 };

// Which discrete gradient drives the momentum equation (eq 2).
enum class GradientVariant {
  // Area-weighted MPS gradient of z_s (eq 6) as printed in the seed paper. Zero for a
  // uniform depth whatever the particle arrangement, so still water stays still. Default.
  mps,
  // Exact gradient of the summed depth (eq 7): grad h_i = sum_j V_j grad W(x_i - x_j).
  // Pairwise antisymmetric, so momentum is conserved to round-off, and the dam-break front
  // runs further; but with the spiky kernel a square lattice at rest is an unstable
  // equilibrium (round-off grows to 0.1 m/s within seconds): see docs/verification.md.
  summation,
};

// How the conservative scheme feels the bed (build.cpp picks the effect).
enum class BedTerm {
  // -g grad z_b at the particle beside the summed depth's force: the gradient of the
  // particles' potential energy, so a closed box never gains energy, but a level surface over a
  // bed rough at the particle scale is not at rest (docs/method.md).
  point,
  // The surface seen through each particle's kernel on the seeding lattice, its corrected
  // gradient in place of the pressure force (swe/balanced_bed_slope.hpp): water filled to a
  // level stays at rest to round-off over any bed. Default.
  balanced,
};

struct Settings {
  double gravity_m_s2 = 9.81;
  double cfl = 0.5;      // eq 13
  SchemeKind scheme = SchemeKind::conservative;
  // Conservative scheme: h_i = kappa sqrt(A_i), the kernel shape, and alpha of the pairwise
  // dissipation (0: none). kappa 1.3 with the cubic spline puts some 20 neighbours in a
  // particle's support and sums uniform water to within 0.4 % (docs/kernels.md).
  double kappa = 1.3;
  KernelShape kernel = KernelShape::cubic_spline;
  double dissipation = 1.0;
  // Conservative scheme: beta of the particle shift D = beta h |u| dt (particle_shifting.hpp;
  // 0: none).
  double shifting = 2.0;
  double alpha_e = 1.3;  // seed scheme, eq 9: r_e = alpha_e sqrt(A_max)
  // eq 9's A_max counts a particle's area only up to this multiple of its creation area A_0,
  // so r_e never exceeds alpha_e sqrt(max_area_ratio A_0); likewise the conservative scheme's
  // h_i never exceeds kappa sqrt(max_area_ratio A_0,i). Without a bound, particles with
  // almost no neighbours feed their kernel-made area back into the radius: an isolated
  // particle has A = 1 / w(0) = 1.26 r_e^2, so r_e would grow x1.46 every step
  // (docs/method.md, "The influence radius"). Unset: the scheme's own default
  // (area_ratio_cap()).
  std::optional<double> max_area_ratio;
  GradientVariant gradient = GradientVariant::mps;  // seed scheme only
  BedTerm bed_term = BedTerm::balanced;             // conservative scheme only
  double min_time_step_s = 1e-8;  // a step below this stops the run: the flow has broken down

  // The cap in force. The seed scheme keeps the 4 its tables were measured with
  // (docs/verification.md). The conservative scheme's radius follows a thinning front further,
  // to 8 A_0 (h up to 2.8 times its first): on the 50 m Ritter dam break that takes the fan
  // error at 0.035 m from 0.48 % to 0.40 % for 5 % more time, where 16 gains 0.37 % for 14 %
  // and, in the valley flood, rows of 150 neighbours in the thin sheets (docs/method.md,
  // "The radius cap").
  double area_ratio_cap() const {
    return max_area_ratio.value_or(scheme == SchemeKind::seed ? 4.0 : 8.0);
  }
};

}  // namespace swemps::swe
