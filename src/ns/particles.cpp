#include "swemps/ns/particles.hpp"

#include <stdexcept>

namespace swemps::ns {

template <int Dim>
void Particles<Dim>::add(Kind kind, const std::array<double, Dim>& x,
                         const std::array<double, Dim>& u) {
  const bool in_order = (kind == Kind::fluid && wall == 0 && dummy == 0) ||
                        (kind == Kind::wall && dummy == 0) || kind == Kind::dummy;
  if (!in_order) throw std::logic_error("ns particles: add fluid, then wall, then dummy");
  for (int d = 0; d < Dim; ++d) {
    position[d].push_back(x[d]);
    velocity[d].push_back(kind == Kind::fluid ? u[d] : 0.0);
  }
  pressure.push_back(0.0);
  (kind == Kind::fluid ? fluid : kind == Kind::wall ? wall : dummy) += 1;
}

template <int Dim>
void Particles<Dim>::remove_fluid(std::span<const char> remove) {
  if (remove.size() != fluid) throw std::invalid_argument("ns particles: one flag per fluid");
  std::size_t kept = 0;
  for (std::size_t i = 0; i < size(); ++i) {
    if (i < fluid && remove[i]) continue;
    for (int d = 0; d < Dim; ++d) {
      position[d][kept] = position[d][i];
      velocity[d][kept] = velocity[d][i];
    }
    pressure[kept] = pressure[i];
    ++kept;
  }
  fluid -= size() - kept;
  for (int d = 0; d < Dim; ++d) {
    position[d].resize(kept);
    velocity[d].resize(kept);
  }
  pressure.resize(kept);
}

template <int Dim>
void Particles<Dim>::reorder_fluid(std::span<const std::uint32_t> order) {
  if (order.size() != fluid) throw std::invalid_argument("ns particles: order must cover fluid");
  std::vector<double> scratch(fluid);
  auto permute = [&](std::vector<double>& values) {
    for (std::size_t k = 0; k < fluid; ++k) scratch[k] = values[order[k]];
    std::copy(scratch.begin(), scratch.end(), values.begin());
  };
  for (int d = 0; d < Dim; ++d) {
    permute(position[d]);
    permute(velocity[d]);
  }
  permute(pressure);
}

template struct Particles<2>;
template struct Particles<3>;

}  // namespace swemps::ns
