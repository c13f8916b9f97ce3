#include "swemps/tsunami/solitary_wave.hpp"

#include <cmath>
#include <stdexcept>

namespace swemps::tsunami {

namespace {

bool finite(const std::array<double, 2>& v) { return std::isfinite(v[0]) && std::isfinite(v[1]); }

}  // namespace

SolitaryWave::SolitaryWave(const SolitaryWaveSpec& spec, double gravity_m_s2)
    : height_m_(spec.height_m),
      depth_m_(spec.still_depth_m),
      gamma_over_depth_(0.0),
      gravity_m_s2_(gravity_m_s2),
      crest_m_(spec.crest_m),
      direction_(spec.direction) {
  if (!(height_m_ > 0.0) || !std::isfinite(height_m_))
    throw std::invalid_argument("solitary wave: the height must be finite and > 0");
  if (!(depth_m_ > height_m_) || !std::isfinite(depth_m_))
    throw std::invalid_argument("solitary wave: the still depth must be finite and > the height");
  if (!(gravity_m_s2 > 0.0) || !std::isfinite(gravity_m_s2))
    throw std::invalid_argument("solitary wave: gravity must be finite and > 0");
  if (!finite(crest_m_)) throw std::invalid_argument("solitary wave: the crest must be finite");
  const double length = std::hypot(direction_[0], direction_[1]);
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument("solitary wave: the direction must be a finite, non-zero vector");
  direction_ = {direction_[0] / length, direction_[1] / length};
  gamma_over_depth_ = std::sqrt(3.0 * height_m_ / (4.0 * depth_m_)) / depth_m_;
}

double SolitaryWave::elevation(double x_m, double y_m) const {
  const double s = (x_m - crest_m_[0]) * direction_[0] + (y_m - crest_m_[1]) * direction_[1];
  const double sech = 1.0 / std::cosh(gamma_over_depth_ * s);
  return height_m_ * sech * sech;
}

std::array<double, 2> SolitaryWave::velocity(double x_m, double y_m) const {
  const double speed = std::sqrt(gravity_m_s2_ / depth_m_) * elevation(x_m, y_m);
  return {speed * direction_[0], speed * direction_[1]};
}

double SolitaryWave::half_length_m() const {
  return std::acosh(std::sqrt(20.0)) / gamma_over_depth_;
}

double SolitaryWave::crest_speed_m_s() const {
  return std::sqrt(gravity_m_s2_ * (depth_m_ + height_m_));
}

}  // namespace swemps::tsunami
