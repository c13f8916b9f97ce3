#include "swemps/maps/hazard.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace swemps::maps {

namespace {

void require_magnitude(double value, const char* what, const char* unit, const char* caller) {
  if (!std::isfinite(value) || value < 0.0) {
    const std::string in_unit = *unit ? std::string(" ") + unit : std::string();
    throw std::invalid_argument(std::string(caller) + ": " + what + " must be finite and >= 0" +
                                in_unit + ", got " + std::to_string(value));
  }
}

// [TR1] Table 3.1, one row per band, one column per LandUse in its declared order.
constexpr std::array<std::array<double, 3>, 3> kDebrisFactor{{
    {0.0, 0.0, 0.0},  // 0 to 0.25 m
    {0.0, 0.5, 1.0},  // 0.25 to 0.75 m
    {0.5, 1.0, 1.0},  // d > 0.75 m and/or v > 2 m/s
}};
constexpr double kShallowDepthM = 0.25;
constexpr double kMidDepthM = 0.75;
constexpr double kFastSpeedMS = 2.0;

double debris_factor_unchecked(double depth_m, double speed_m_s, LandUse land) {
  if (depth_m == 0.0) return 0.0;  // dry: no water to carry debris (see the header)
  const std::size_t band = (depth_m > kMidDepthM || speed_m_s > kFastSpeedMS) ? 2
                           : depth_m > kShallowDepthM                         ? 1
                                                                              : 0;
  const auto column = static_cast<std::size_t>(land);
  if (column >= 3) throw std::invalid_argument("debris_factor: unknown land use");
  return kDebrisFactor[band][column];
}

// [AIDR] Table 2, H1 to H5; a cell within none of them is H6.
struct AidrLimits {
  double depth_m, speed_m_s, depth_speed_m2_s;
};
constexpr std::array<AidrLimits, 5> kAidrLimits{{
    {0.3, 2.0, 0.3},  // H1
    {0.5, 2.0, 0.6},  // H2
    {1.2, 2.0, 0.6},  // H3
    {2.0, 2.0, 1.0},  // H4
    {4.0, 4.0, 4.0},  // H5
}};

}  // namespace

double debris_factor(double depth_m, double speed_m_s, LandUse land) {
  require_magnitude(depth_m, "the depth", "m", "debris_factor");
  require_magnitude(speed_m_s, "the speed", "m/s", "debris_factor");
  return debris_factor_unchecked(depth_m, speed_m_s, land);
}

double uk_hazard_rating(double depth_m, double speed_m_s, LandUse land) {
  require_magnitude(depth_m, "the depth", "m", "uk_hazard_rating");
  require_magnitude(speed_m_s, "the speed", "m/s", "uk_hazard_rating");
  // The 0.5 m/s stands in for the hazard of deep still water, which a rating of d v alone
  // would call harmless.
  return depth_m * (speed_m_s + 0.5) + debris_factor_unchecked(depth_m, speed_m_s, land);
}

UkHazardClass uk_hazard_class(double rating) {
  require_magnitude(rating, "the hazard rating", "", "uk_hazard_class");
  if (rating < 0.75) return UkHazardClass::low;        // "less than 0.75"
  if (rating <= 1.25) return UkHazardClass::moderate;  // our reading of the shared 1.25
  if (rating <= 2.0) return UkHazardClass::significant;
  return UkHazardClass::extreme;  // "more than 2.0"
}

AidrHazard aidr_hazard(double depth_m, double speed_m_s) {
  require_magnitude(depth_m, "the depth", "m", "aidr_hazard");
  require_magnitude(speed_m_s, "the speed", "m/s", "aidr_hazard");
  if (depth_m == 0.0) return AidrHazard::h1;  // dry (see the header)
  const double depth_speed_m2_s = depth_m * speed_m_s;
  // The limits grow class by class, so the first class that holds the cell is its class.
  for (std::size_t k = 0; k < kAidrLimits.size(); ++k) {
    const AidrLimits& l = kAidrLimits[k];
    if (depth_m <= l.depth_m && speed_m_s <= l.speed_m_s &&
        depth_speed_m2_s <= l.depth_speed_m2_s) {
      return static_cast<AidrHazard>(k + 1);
    }
  }
  return AidrHazard::h6;
}

std::string_view name(LandUse land) {
  switch (land) {
    case LandUse::pasture_arable: return "pasture/arable";
    case LandUse::woodland: return "woodland";
    case LandUse::urban: return "urban";
  }
  return "unknown land use";
}

std::string_view name(UkHazardClass hazard) {
  switch (hazard) {
    case UkHazardClass::low: return "low: caution";
    case UkHazardClass::moderate: return "moderate: danger for some";
    case UkHazardClass::significant: return "significant: danger for most";
    case UkHazardClass::extreme: return "extreme: danger for all";
  }
  return "unknown hazard class";
}

std::string_view name(AidrHazard hazard) {
  switch (hazard) {
    case AidrHazard::h1: return "H1: generally safe for vehicles, people and buildings";
    case AidrHazard::h2: return "H2: unsafe for small vehicles";
    case AidrHazard::h3: return "H3: unsafe for vehicles, children and the elderly";
    case AidrHazard::h4: return "H4: unsafe for vehicles and people";
    case AidrHazard::h5:
      return "H5: unsafe for vehicles and people; all buildings vulnerable to structural damage, "
             "some less robust buildings subject to failure";
    case AidrHazard::h6:
      return "H6: unsafe for vehicles and people; all building types considered vulnerable to "
             "failure";
  }
  return "unknown hazard class";
}

}  // namespace swemps::maps
