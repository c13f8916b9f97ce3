// key=value options shared by the Navier-Stokes benchmarks: each changes one default of
// ns::Settings, so the standard scheme and the well-balanced options can be timed and
// compared from the command line.
//
// Keys: scheme=standard|well-balanced|least-squares (every numerical choice of that scheme;
// later keys override), operators=mps|least-squares, source=number-density|mixed, gamma=G,
// gradient=minimum|corrected|corrected-repulsive, gradient-weights=mps|kernel-slope,
// boundary=poisson|extrapolated, repulsion=R, asymmetry=A, kernel=NAME, support=S, beta=B, courant=C, tolerance=T, compression=E
// (solver.compression_tolerance), preconditioner=ic|diagonal|multigrid, multigrid-setup=N
// (solver.multigrid_setup_solves), collision=off.
#pragma once

#include <cstdlib>
#include <string>

#include "swemps/ns/settings.hpp"

namespace swemps::benchmarks {

// Applies one key=value argument to the settings of a run in `dimensions`; returns false for an
// unknown key or value.
inline bool apply_ns_option(const std::string& argument, ns::Settings& s, int dimensions) {
  const auto eq = argument.find('=');
  if (eq == std::string::npos) return false;
  const std::string key = argument.substr(0, eq), value = argument.substr(eq + 1);
  const double number = std::atof(value.c_str());
  if (key == "scheme") {
    if (value != "standard" && value != "well-balanced" && value != "least-squares") return false;
    const double spacing = s.spacing_m;
    s = ns::scheme_settings(value == "standard"        ? ns::Scheme::standard
                            : value == "least-squares" ? ns::Scheme::least_squares
                                                       : ns::Scheme::well_balanced,
                            dimensions);
    s.spacing_m = spacing;
  } else if (key == "operators") {
    if (value != "mps" && value != "least-squares") return false;
    s.operators = value == "mps" ? ns::Operators::mps : ns::Operators::least_squares;
  } else if (key == "source") {
    s.source = value == "mixed" ? ns::SourceTerm::mixed : ns::SourceTerm::number_density;
  } else if (key == "gamma") {
    s.source_gamma = number;
  } else if (key == "gradient") {
    s.gradient = value == "corrected"             ? ns::PressureGradient::corrected
                 : value == "corrected-repulsive" ? ns::PressureGradient::corrected_repulsive
                                                  : ns::PressureGradient::minimum_pressure;
  } else if (key == "kernel") {
    const auto type = kernels::kernel_type_from_name(value);
    if (!type) return false;
    s.pressure_kernel.spec.type = *type;
    s.velocity_kernel.spec.type = *type;
  } else if (key == "support") {
    s.pressure_kernel.support_spacings = number;
    s.velocity_kernel.support_spacings = number;
  } else if (key == "gradient-weights") {
    const auto weights = ns::gradient_weights_from_name(value);
    if (!weights) return false;
    s.gradient_weights = *weights;
  } else if (key == "repulsion") {
    s.repulsion_distance_spacings = number;
  } else if (key == "asymmetry") {
    s.free_surface_asymmetry = number;
  } else if (key == "boundary") {
    s.boundary = value == "extrapolated" ? ns::BoundaryPressure::extrapolated
                                         : ns::BoundaryPressure::poisson;
  } else if (key == "beta") {
    s.free_surface_beta = number;
  } else if (key == "courant") {
    s.courant = number;
  } else if (key == "tolerance") {
    s.solver.relative_tolerance = number;
  } else if (key == "compression") {
    s.solver.compression_tolerance = number;
  } else if (key == "multigrid-setup") {
    s.solver.multigrid_setup_solves = static_cast<int>(number);
  } else if (key == "preconditioner") {
    const auto p = ns::preconditioner_from_name(value == "ic" ? "incomplete-cholesky" : value);
    if (!p) return false;
    s.solver.preconditioner = *p;
  } else if (key == "collision") {
    if (value == "off") s.collision.reset();
  } else {
    return false;
  }
  return true;
}

}  // namespace swemps::benchmarks
