#pragma once
// One kernel chosen at run time from a scene (method.md section 2): the six weights as a
// variant, their scene names, and a factory that sizes each by its cut-off distance. Solvers
// that want the inner loop free of the dispatch visit the variant once, outside the loop, and
// run a loop templated on the concrete kernel; weight() and support() are for everything else.

#include <array>
#include <optional>
#include <span>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <variant>

#include "swemps/kernels/hyperbolic_mps.hpp"
#include "swemps/kernels/hyperbolic_sph.hpp"
#include "swemps/kernels/logarithmic.hpp"
#include "swemps/kernels/sheu_quartic.hpp"
#include "swemps/kernels/spiky.hpp"
#include "swemps/kernels/standard.hpp"

namespace swemps::kernels {

enum class KernelType {
  standard,
  sheu_quartic,
  logarithmic,
  hyperbolic_mps,
  hyperbolic_sph,
  spiky
};

// What a scene says about its kernel. kappa is used by both hyperbolic kernels, theta only by
// the MPS one (it cancels in every MPS operator, which divides by n0).
struct KernelSpec {
  KernelType type = KernelType::standard;
  double kappa = 2.0;
  double theta = 1.0;
};

namespace detail {
// Scene names, in KernelType order.
inline constexpr std::array<std::string_view, 6> kernel_names{
    "standard", "sheu-quartic", "logarithmic", "hyperbolic", "hyperbolic-sph", "spiky"};
}  // namespace detail

inline std::string_view kernel_type_name(KernelType type) {
  return detail::kernel_names.at(static_cast<std::size_t>(type));
}

inline std::optional<KernelType> kernel_type_from_name(std::string_view name) {
  for (std::size_t k = 0; k < detail::kernel_names.size(); ++k) {
    if (detail::kernel_names[k] == name) return static_cast<KernelType>(k);
  }
  return std::nullopt;
}

// Every valid scene name, for error messages.
inline std::span<const std::string_view> kernel_type_names() { return detail::kernel_names; }

template <int Dim>
using AnyKernel = std::variant<StandardMps, SheuQuartic, Logarithmic, HyperbolicMps,
                               HyperbolicSph<Dim>, Spiky<Dim>>;

// The kernel whose support() equals support_radius (the cut-off distance, m), so that one
// neighbour-search radius serves every choice: r_e = support_radius for the MPS weights, whose
// support is r_e, and r_e = support_radius / 2 for the SPH-type kernels, whose support is 2 r_e
// (halving and doubling are exact in binary, so support() returns support_radius itself).
// Invalid radii or parameters throw std::invalid_argument from the kernel's constructor.
template <int Dim>
AnyKernel<Dim> make_kernel(const KernelSpec& spec, double support_radius) {
  switch (spec.type) {
    case KernelType::standard: return StandardMps(support_radius);
    case KernelType::sheu_quartic: return SheuQuartic(support_radius);
    case KernelType::logarithmic: return Logarithmic(support_radius);
    case KernelType::hyperbolic_mps: return HyperbolicMps(support_radius, spec.kappa, spec.theta);
    case KernelType::hyperbolic_sph: return HyperbolicSph<Dim>(0.5 * support_radius, spec.kappa);
    case KernelType::spiky: return Spiky<Dim>(0.5 * support_radius);
  }
  throw std::invalid_argument("make_kernel: unknown kernel type");
}

template <int Dim>
double weight(const AnyKernel<Dim>& kernel, double r) {
  return std::visit([r](const auto& k) { return k.w(r); }, kernel);
}

template <int Dim>
double support(const AnyKernel<Dim>& kernel) {
  return std::visit([](const auto& k) { return k.support(); }, kernel);
}

template <int Dim>
bool singular_at_origin(const AnyKernel<Dim>& kernel) {
  return std::visit([](const auto& k) { return std::decay_t<decltype(k)>::singular_at_origin; },
                    kernel);
}

}  // namespace swemps::kernels
