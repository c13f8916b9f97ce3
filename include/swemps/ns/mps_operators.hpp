#pragma once
// The standard MPS pressure operators (method.md section 3; Koshizuka & Oka 1996): the
// Laplacian (2d / (lambda n0)) sum_j (p_j - p_i) w_ij with the kernel's lattice constants,
// whose Poisson matrix is symmetric positive definite (poisson.hpp, boundary_pressure.hpp),
// and the pressure gradient Settings::gradient names, with the pair weights
// Settings::gradient_weights names (settings.hpp).

#include <optional>

#include "swemps/kernels/any_kernel.hpp"
#include "swemps/ns/pressure_operators.hpp"

namespace swemps::ns {

template <int Dim>
class MpsOperators final : public PressureOperators<Dim> {
 public:
  // The settings' pressure kernel gives the gradient's pair weights with
  // GradientWeights::kernel_slope.
  explicit MpsOperators(const Settings& settings);
  std::string_view name() const override { return "mps"; }
  void assemble(const StepGeometry<Dim>& g, std::vector<char>& unknown,
                std::span<const double> source, const BoundaryExtrapolation* boundary,
                PoissonSystem& out) override;
  void velocity_change(const StepGeometry<Dim>& g, double dt,
                       std::array<std::vector<double>, Dim>& change) override;

 private:
  // velocity_change on the concrete kernel: slope(r^2) is the pair weight -w'(r) / r of
  // GradientWeights::kernel_slope (settings.hpp), or a stand-in the MPS weights never read.
  template <class Slope>
  void gradient_loop(const StepGeometry<Dim>& g, double dt, Slope slope,
                     std::array<std::vector<double>, Dim>& change) const;

  std::optional<kernels::AnyKernel<Dim>> slope_kernel_;  // kernel_slope only
};

// Solves C g = b for a symmetric Dim x Dim matrix; false when C is too close to singular
// (a particle with neighbours on one line or plane only): det C below 5 % of the product of
// its diagonal, i.e. a correlation between axes above about 0.97 (2D). A flat surface or a
// corner keeps det C near that product; two neighbours nearly in line would amplify the
// pressure differences without bound.
template <int Dim>
bool solve_symmetric(const std::array<std::array<double, Dim>, Dim>& c,
                     const std::array<double, Dim>& b, std::array<double, Dim>& g);

extern template class MpsOperators<2>;
extern template class MpsOperators<3>;

}  // namespace swemps::ns
