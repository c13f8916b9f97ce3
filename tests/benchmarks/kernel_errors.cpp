// How accurate the MPS gradient and Laplacian (method.md section 3) are with each weight of
// method.md section 2, on a square (2D) or cubic (3D) lattice of spacing l0 whose particles are
// displaced at random. Prints the markdown tables of docs/kernels.md; the text there explains
// how to read them. Everything is in units of l0 (l0 = 1).
//
//   gradient   <grad phi>_i = (d / n0) sum_j (phi_j - phi_i) x_ij w_ij / r_ij^2
//   Laplacian  <lap phi>_i  = (2d / (lambda n0)) sum_j (phi_j - phi_i) w_ij,
//              lambda = sum_j r_ij^2 w_ij / sum_j w_ij
//
// with n0 and lambda from the unperturbed lattice, as an MPS solver takes them.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "swemps/kernels/any_kernel.hpp"

namespace {

using swemps::kernels::KernelSpec;
using swemps::kernels::KernelType;

// Particles farther than this from the lattice edge see a full neighbourhood for every support
// below (4 l0, plus up to 2 * 0.2 l0 of displacement, plus one spacing of slack).
constexpr int edge_margin = 6;
// Errors are averaged over this many particles per side: 2304 in 2D, 4096 in 3D.
constexpr std::array<int, 4> interior_side{0, 0, 48, 16};
// Wavelength L of the smooth test fields (see operator_errors) in the main tables.
constexpr double table_wave_length = 10.0;
// One seed for every row: all kernels and supports see the same particles, and eps = 0.2
// displaces them exactly twice as far as eps = 0.1.
constexpr std::uint64_t seed = 20240611;
constexpr std::array<double, 2> perturbations{0.1, 0.2};
constexpr std::array<double, 4> supports{2.0, 2.1, 3.1, 4.0};

struct KernelChoice {
  std::string label;
  KernelSpec spec;
};

std::vector<KernelChoice> kernel_choices() {
  return {{"standard", {KernelType::standard}},
          {"sheu-quartic", {KernelType::sheu_quartic}},
          {"logarithmic", {KernelType::logarithmic}},
          {"hyperbolic, kappa 2", {KernelType::hyperbolic_mps, 2.0}},
          {"hyperbolic, kappa 3", {KernelType::hyperbolic_mps, 3.0}},
          {"hyperbolic, kappa 4", {KernelType::hyperbolic_mps, 4.0}},
          {"hyperbolic-sph, kappa 2", {KernelType::hyperbolic_sph, 2.0}},
          {"spiky", {KernelType::spiky}}};
}

// SplitMix64: a fixed, platform-independent stream (std::uniform_real_distribution is not
// specified bit for bit, and the tables should reproduce anywhere).
class UniformStream {
 public:
  explicit UniformStream(std::uint64_t state) : state_(state) {}
  // Uniform in [-1, 1).
  double next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return 2.0 * static_cast<double>(z >> 11) * 0x1.0p-53 - 1.0;
  }

 private:
  std::uint64_t state_;
};

template <int Dim>
using Point = std::array<double, Dim>;

// A Dim-dimensional lattice, side^Dim sites at integer coordinates, each displaced by
// eps * (uniform in [-1, 1)) per coordinate.
template <int Dim>
struct Lattice {
  int side = 0;
  std::vector<Point<Dim>> position;

  Lattice(int side_sites, double eps) : side(side_sites) {
    UniformStream uniform(seed);
    int sites = 1;
    for (int a = 0; a < Dim; ++a) sites *= side;
    position.resize(sites);
    for (int n = 0; n < sites; ++n) {
      const auto index = unflatten(n);
      for (int a = 0; a < Dim; ++a) position[n][a] = index[a] + eps * uniform.next();
    }
  }

  std::array<int, Dim> unflatten(int n) const {
    std::array<int, Dim> index{};
    for (int a = 0; a < Dim; ++a) {
      index[a] = n % side;
      n /= side;
    }
    return index;
  }

  int flatten(const std::array<int, Dim>& index) const {
    int n = 0;
    for (int a = Dim - 1; a >= 0; --a) n = n * side + index[a];
    return n;
  }
};

// Every integer offset in [-reach, reach]^Dim except the origin: the lattice neighbours a
// particle may have within the support, before and after the displacement.
template <int Dim>
std::vector<std::array<int, Dim>> offsets_within(int reach) {
  std::vector<std::array<int, Dim>> offsets;
  const int width = 2 * reach + 1;
  int count = 1;
  for (int a = 0; a < Dim; ++a) count *= width;
  for (int n = 0; n < count; ++n) {
    std::array<int, Dim> offset{};
    bool origin = true;
    for (int a = 0, rest = n; a < Dim; ++a, rest /= width) {
      offset[a] = rest % width - reach;
      origin = origin && offset[a] == 0;
    }
    if (!origin) offsets.push_back(offset);
  }
  return offsets;
}

// Sum of squared errors and of squared exact values, for an RMS relative error.
struct ErrorSum {
  double error_squared = 0.0;
  double exact_squared = 0.0;
  void add(double error, double exact) {
    error_squared += error * error;
    exact_squared += exact * exact;
  }
  double relative_rms() const { return std::sqrt(error_squared / exact_squared); }
};

// What the unperturbed lattice gives for one kernel.
struct LatticeConstants {
  int neighbours = 0;
  double n0 = 0.0;
  double lambda = 0.0;
};

template <int Dim, class Kernel>
LatticeConstants lattice_constants(const Kernel& kernel,
                                   const std::vector<std::array<int, Dim>>& offsets) {
  LatticeConstants c;
  double second_moment = 0.0;
  for (const auto& offset : offsets) {
    double r2 = 0.0;
    for (int a = 0; a < Dim; ++a) r2 += offset[a] * offset[a];
    const double w = kernel.w(std::sqrt(r2));
    if (w == 0.0) continue;
    ++c.neighbours;
    c.n0 += w;
    second_moment += r2 * w;
  }
  c.lambda = second_moment / c.n0;
  return c;
}

struct OperatorErrors {
  double laplacian_quadratic = 0.0;
  double gradient_wave = 0.0;
  double laplacian_wave = 0.0;
  double laplacian_harmonic = 0.0;
};

// Applies both operators at every interior particle, to three fields:
// - the quadratic |x - x_i|^2, taken about the particle itself so that phi_j - phi_i = r_ij^2
//   and the exact Laplacian is 2d (about a fixed origin, x^2 + y^2 adds a linear field whose
//   error grows with the distance to that origin, an artefact of where the origin is);
// - the wave sin(x / L) cos(y / L) [cos(z / L)], gradient and Laplacian;
// - the harmonic exp(sqrt(d - 1) x / L) cos(y / L) [cos(z / L)], whose exact Laplacian is 0:
//   the error is measured against the RMS of its d^2 phi / dx^2 = (d - 1) phi / L^2. On the
//   unperturbed lattice at support 2 l0 this is the nine-point Laplacian Sheu et al. make
//   fourth-order accurate for harmonic fields (their eq 4.5).
template <int Dim, class Kernel>
OperatorErrors operator_errors(const Kernel& kernel, const Lattice<Dim>& lattice,
                               const std::vector<std::array<int, Dim>>& offsets,
                               const LatticeConstants& c, double wave_length) {
  const auto wave = [wave_length](const Point<Dim>& x) {
    double value = std::sin(x[0] / wave_length);
    for (int a = 1; a < Dim; ++a) value *= std::cos(x[a] / wave_length);
    return value;
  };
  const auto wave_gradient = [wave_length](const Point<Dim>& x) {
    Point<Dim> g{};
    for (int a = 0; a < Dim; ++a) {
      g[a] = (a == 0 ? std::cos(x[0] / wave_length) : -std::sin(x[a] / wave_length)) / wave_length;
      for (int b = 0; b < Dim; ++b) {
        if (b != a) g[a] *= b == 0 ? std::sin(x[0] / wave_length) : std::cos(x[b] / wave_length);
      }
    }
    return g;
  };
  const double harmonic_rate = std::sqrt(Dim - 1.0) / wave_length;
  const auto harmonic = [wave_length, harmonic_rate](const Point<Dim>& x) {
    double value = std::exp(harmonic_rate * x[0]);
    for (int a = 1; a < Dim; ++a) value *= std::cos(x[a] / wave_length);
    return value;
  };

  ErrorSum lap_quadratic, grad_wave, lap_wave, lap_harmonic;
  const double laplacian_scale = 2.0 * Dim / (c.lambda * c.n0);
  const int first = edge_margin, last = edge_margin + interior_side[Dim];
  for (int n = 0; n < static_cast<int>(lattice.position.size()); ++n) {
    const auto index = lattice.unflatten(n);
    bool interior = true;
    for (int a = 0; a < Dim; ++a) interior = interior && index[a] >= first && index[a] < last;
    if (!interior) continue;
    const Point<Dim>& xi = lattice.position[n];
    const double wave_i = wave(xi), harmonic_i = harmonic(xi);
    double sum_r2_w = 0.0, sum_wave_w = 0.0, sum_harmonic_w = 0.0;
    Point<Dim> sum_gradient{};
    for (const auto& offset : offsets) {
      std::array<int, Dim> neighbour = index;
      for (int a = 0; a < Dim; ++a) neighbour[a] += offset[a];
      const Point<Dim>& xj = lattice.position[lattice.flatten(neighbour)];
      Point<Dim> xij{};
      double r2 = 0.0;
      for (int a = 0; a < Dim; ++a) {
        xij[a] = xj[a] - xi[a];
        r2 += xij[a] * xij[a];
      }
      const double w = kernel.w(std::sqrt(r2));
      if (w == 0.0) continue;
      const double d_wave = wave(xj) - wave_i;
      sum_r2_w += r2 * w;
      sum_wave_w += d_wave * w;
      sum_harmonic_w += (harmonic(xj) - harmonic_i) * w;
      for (int a = 0; a < Dim; ++a) sum_gradient[a] += d_wave * xij[a] * w / r2;
    }
    lap_quadratic.add(laplacian_scale * sum_r2_w - 2.0 * Dim, 2.0 * Dim);
    const double wave_laplacian = -Dim * wave_i / (wave_length * wave_length);
    lap_wave.add(laplacian_scale * sum_wave_w - wave_laplacian, wave_laplacian);
    lap_harmonic.add(laplacian_scale * sum_harmonic_w,
                     (Dim - 1.0) * harmonic_i / (wave_length * wave_length));
    const Point<Dim> exact = wave_gradient(xi);
    double error_squared = 0.0, exact_squared = 0.0;
    for (int a = 0; a < Dim; ++a) {
      const double error = Dim / c.n0 * sum_gradient[a] - exact[a];
      error_squared += error * error;
      exact_squared += exact[a] * exact[a];
    }
    grad_wave.add(std::sqrt(error_squared), std::sqrt(exact_squared));
  }
  return {lap_quadratic.relative_rms(), grad_wave.relative_rms(), lap_wave.relative_rms(),
          lap_harmonic.relative_rms()};
}

// One table row: a kernel at one support, on the unperturbed and the perturbed lattices.
struct Row {
  std::string label;
  double support = 0.0;
  LatticeConstants constants;
  OperatorErrors unperturbed;
  std::array<OperatorErrors, perturbations.size()> perturbed;
};

template <int Dim>
std::vector<Row> measure_rows(const std::vector<std::array<int, Dim>>& offsets) {
  const int side = interior_side[Dim] + 2 * edge_margin;
  const Lattice<Dim> regular(side, 0.0);
  std::vector<Lattice<Dim>> perturbed;
  for (const double eps : perturbations) perturbed.emplace_back(side, eps);
  std::vector<Row> rows;
  for (const double support : supports) {
    for (const auto& choice : kernel_choices()) {
      Row row;
      row.label = choice.label;
      row.support = support;
      // One visit per row; the sums below run on the concrete kernel type.
      std::visit(
          [&](const auto& kernel) {
            row.constants = lattice_constants<Dim>(kernel, offsets);
            row.unperturbed =
                operator_errors<Dim>(kernel, regular, offsets, row.constants, table_wave_length);
            for (std::size_t k = 0; k < perturbed.size(); ++k) {
              row.perturbed[k] = operator_errors<Dim>(kernel, perturbed[k], offsets, row.constants,
                                                      table_wave_length);
            }
          },
          swemps::kernels::make_kernel<Dim>(choice.spec, support));
      rows.push_back(row);
    }
  }
  return rows;
}

// Relative error as a percentage, three significant digits.
std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", 100.0 * fraction);
  return text;
}

template <int Dim>
void print_tables() {
  // Offsets reach past the largest support by the largest displacement of a pair.
  const auto offsets = offsets_within<Dim>(edge_margin - 1);
  const auto rows = measure_rows<Dim>(offsets);

  std::printf("### %dD, unperturbed lattice: lattice constants and RMS relative error (%%)\n\n",
              Dim);
  std::printf(
      "| kernel | support / l0 | neighbours | n0 | lambda / l0^2 | grad, wave |"
      " Laplacian, wave | Laplacian, harmonic |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const auto& row : rows) {
    std::printf("| %s | %.1f | %d | %.4g | %.4g | %s | %s | %s |\n", row.label.c_str(), row.support,
                row.constants.neighbours, row.constants.n0, row.constants.lambda,
                percent(row.unperturbed.gradient_wave).c_str(),
                percent(row.unperturbed.laplacian_wave).c_str(),
                percent(row.unperturbed.laplacian_harmonic).c_str());
  }

  std::printf("\n### %dD, perturbed lattice: RMS relative error (%%)\n\n", Dim);
  std::printf("| kernel | support / l0 |");
  for (const double eps : perturbations) {
    std::printf(" eps %.1f: Laplacian, quadratic | grad, wave | Laplacian, wave |", eps);
  }
  std::printf("\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& row : rows) {
    std::printf("| %s | %.1f |", row.label.c_str(), row.support);
    for (const auto& e : row.perturbed) {
      std::printf(" %s | %s | %s |", percent(e.laplacian_quadratic).c_str(),
                  percent(e.gradient_wave).c_str(), percent(e.laplacian_wave).c_str());
    }
    std::printf("\n");
  }
  std::printf("\n");
}

// The wave's Laplacian error on the perturbed lattice is mostly the operator's response to the
// wave's gradient, which grows relative to the Laplacian as L / l0 grows: shown here at one
// support and eps = 0.1 for wavelengths from 5 to 40 l0.
void print_wavelength_table() {
  constexpr int dim = 2;
  constexpr double support = 4.0;
  constexpr std::array<double, 4> lengths{5.0, 10.0, 20.0, 40.0};
  const auto offsets = offsets_within<dim>(edge_margin - 1);
  const Lattice<dim> lattice(interior_side[dim] + 2 * edge_margin, perturbations[0]);
  std::printf(
      "### 2D, eps %.1f, support %.1f l0: Laplacian of the wave against its wavelength,"
      " RMS relative error (%%)\n\n| kernel |",
      perturbations[0], support);
  for (const double length : lengths) std::printf(" L = %.0f l0 |", length);
  std::printf("\n|---|---|---|---|---|\n");
  for (const auto& choice : kernel_choices()) {
    std::printf("| %s |", choice.label.c_str());
    std::visit(
        [&](const auto& kernel) {
          const auto constants = lattice_constants<dim>(kernel, offsets);
          for (const double length : lengths) {
            const auto e = operator_errors<dim>(kernel, lattice, offsets, constants, length);
            std::printf(" %s |", percent(e.laplacian_wave).c_str());
          }
        },
        swemps::kernels::make_kernel<dim>(choice.spec, support));
    std::printf("\n");
  }
}

}  // namespace

int main() {
  std::printf(
      "<!-- swemps-kernel-errors: seed %llu, interior %d x %d (2D), %d^3 (3D),"
      " wave length %.0f l0 -->\n\n",
      static_cast<unsigned long long>(seed), interior_side[2], interior_side[2], interior_side[3],
      table_wave_length);
  print_tables<2>();
  print_tables<3>();
  print_wavelength_table();
  return 0;
}
