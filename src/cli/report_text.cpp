#include "swemps/cli/report_text.hpp"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace swemps::cli {

std::string count(double v) {
  if (!std::isfinite(v)) return "?";
  const std::string digits = fmt::format("{:.0f}", std::max(0.0, v));
  std::string out;
  for (std::size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return out;
}

std::string num(double v) {
  const double a = std::abs(v);
  if (a >= 1e4 && a < 1e9) return fmt::format("{}{}", v < 0.0 ? "-" : "", count(a));
  if (a == 0.0 || (a >= 1e-3 && a < 1e4)) return fmt::format("{:.4g}", v);
  return fmt::format("{:.3g}", v);
}

std::string duration(double s) {
  if (s < 60.0) return fmt::format("{:.2g} s", s);
  if (s < 3600.0) {
    const auto whole = static_cast<long>(std::lround(s));
    return fmt::format("{} min {} s", whole / 60, whole % 60);
  }
  const auto minutes = static_cast<long>(std::lround(s / 60.0));
  return fmt::format("{} h {} min", minutes / 60, minutes % 60);
}

void heading(const std::string& title) { std::printf("\n%s\n", title.c_str()); }

void row(const std::string& label, const std::string& value) {
  std::printf("  %-24s %s\n", label.c_str(), value.c_str());
}

}  // namespace swemps::cli
