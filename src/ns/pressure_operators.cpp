#include "swemps/ns/pressure_operators.hpp"

#include "swemps/ns/least_squares_operators.hpp"
#include "swemps/ns/mps_operators.hpp"

namespace swemps::ns {

template <int Dim>
std::unique_ptr<PressureOperators<Dim>> make_pressure_operators(const Settings& settings) {
  if (settings.operators == Operators::least_squares) {
    return std::make_unique<LeastSquaresOperators<Dim>>();
  }
  return std::make_unique<MpsOperators<Dim>>(settings);
}

template std::unique_ptr<PressureOperators<2>> make_pressure_operators<2>(const Settings&);
template std::unique_ptr<PressureOperators<3>> make_pressure_operators<3>(const Settings&);

}  // namespace swemps::ns
