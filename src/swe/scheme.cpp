#include "swemps/swe/scheme.hpp"

#include "swemps/swe/conservative_scheme.hpp"
#include "swemps/swe/seed_scheme.hpp"

namespace swemps::swe {

std::string_view kernel_shape_name(KernelShape shape) {
  switch (shape) {
    case KernelShape::spiky: return "spiky";
    case KernelShape::wendland_c2: return "wendland-c2";
    case KernelShape::cubic_spline: break;
  }
  return "cubic-spline";
}

std::unique_ptr<Scheme> make_scheme(const Settings& settings) {
  switch (settings.scheme) {
    case SchemeKind::conservative: return std::make_unique<ConservativeScheme>(settings);
    case SchemeKind::seed: break;
  }
  return std::make_unique<SeedScheme>(settings);
}

}  // namespace swemps::swe
