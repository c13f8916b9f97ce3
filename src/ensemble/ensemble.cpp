#include "swemps/ensemble/ensemble.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace swemps::ensemble {

namespace {

// SplitMix64 (Steele, Lea & Flood 2014): a generator whose every output is fixed by its
// seed, unlike the standard library's distributions, whose algorithms each library chooses.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31U);
  }
  // A fraction in [0, 1) with 53 random bits: every double it gives is exact.
  double unit() { return static_cast<double>(next() >> 11U) * 0x1.0p-53; }
  // A whole number in [0, n), n > 0, without bias: draws below 2^64 mod n are refused, so
  // that every remainder is as likely (a refusal is rarer than n / 2^64).
  std::size_t below(std::size_t n) {
    const std::uint64_t refused = (0 - static_cast<std::uint64_t>(n)) % n;
    for (;;) {
      const std::uint64_t x = next();
      if (x >= refused) return static_cast<std::size_t>(x % n);
    }
  }

 private:
  std::uint64_t state_;
};

// One stream per sampled knob, so that adding a knob at the end leaves the others' draws as
// they were.
SplitMix64 knob_stream(std::uint64_t seed, std::size_t knob) {
  SplitMix64 mix(seed ^ (0x5851f42d4c957f2dULL * (static_cast<std::uint64_t>(knob) + 1)));
  return SplitMix64(mix.next());
}

// A fraction of the range as a value of the knob.
double knob_value(const Knob& knob, double fraction) {
  if (knob.distribution == Distribution::log_uniform) {
    const double a = std::log(knob.low), b = std::log(knob.high);
    return std::exp(a + fraction * (b - a));
  }
  return knob.low + fraction * (knob.high - knob.low);
}

// The shortest text that reads back as the same double.
std::string shortest_text(double v) {
  std::array<char, 32> text{};
  const auto end = std::to_chars(text.data(), text.data() + text.size(), v).ptr;
  return std::string(text.data(), end);
}

}  // namespace

std::size_t member_count(const Ensemble& ensemble) {
  std::size_t count = ensemble.samples;
  for (const Knob& k : ensemble.knobs) {
    if (!k.sampled()) count *= k.values.size();
  }
  return count;
}

std::vector<std::vector<double>> unit_draws(std::size_t samples, std::size_t knobs,
                                            std::uint64_t seed, Sampling sampling) {
  std::vector<std::vector<double>> draws(samples, std::vector<double>(knobs, 0.0));
  for (std::size_t k = 0; k < knobs; ++k) {
    SplitMix64 stream = knob_stream(seed, k);
    if (sampling == Sampling::random) {
      for (std::size_t s = 0; s < samples; ++s) draws[s][k] = stream.unit();
      continue;
    }
    // Latin hypercube: a random permutation of the strata (Fisher-Yates), then one uniform
    // draw within each stratum.
    std::vector<std::size_t> stratum(samples);
    std::iota(stratum.begin(), stratum.end(), std::size_t{0});
    for (std::size_t i = samples; i > 1; --i) std::swap(stratum[i - 1], stratum[stream.below(i)]);
    for (std::size_t s = 0; s < samples; ++s) {
      draws[s][k] =
          (static_cast<double>(stratum[s]) + stream.unit()) / static_cast<double>(samples);
    }
  }
  return draws;
}

namespace {

// Member `index`, from the draws of every sample (unit_draws of the sampled knobs).
Member make_member(const Ensemble& ensemble, std::size_t index,
                   const std::vector<std::vector<double>>& draws) {
  Member m{index, std::vector<std::string>(ensemble.knobs.size())};
  const std::size_t sample = index % ensemble.samples;
  // The combination's digits, the last listed knob fastest; sampled knobs in their order.
  std::size_t combination = index / ensemble.samples;
  std::size_t sampled = draws.empty() ? 0 : draws.front().size();
  for (std::size_t k = ensemble.knobs.size(); k-- > 0;) {
    const Knob& knob = ensemble.knobs[k];
    if (knob.sampled()) {
      m.values[k] = shortest_text(knob_value(knob, draws[sample][--sampled]));
      continue;
    }
    m.values[k] = knob.values[combination % knob.values.size()];
    combination /= knob.values.size();
  }
  return m;
}

std::vector<std::vector<double>> draws_of(const Ensemble& ensemble) {
  const auto sampled = static_cast<std::size_t>(std::count_if(
      ensemble.knobs.begin(), ensemble.knobs.end(), [](const Knob& k) { return k.sampled(); }));
  return unit_draws(ensemble.samples, sampled, ensemble.seed, ensemble.sampling);
}

}  // namespace

std::vector<Member> members(const Ensemble& ensemble) {
  const auto draws = draws_of(ensemble);
  const std::size_t count = member_count(ensemble);
  std::vector<Member> out;
  out.reserve(count);
  for (std::size_t index = 0; index < count; ++index) {
    out.push_back(make_member(ensemble, index, draws));
  }
  return out;
}

Member member(const Ensemble& ensemble, std::size_t index) {
  if (index >= member_count(ensemble)) {
    throw std::out_of_range("ensemble::member: " + std::to_string(index) + " of " +
                            std::to_string(member_count(ensemble)) + " members");
  }
  return make_member(ensemble, index, draws_of(ensemble));
}

std::string member_folder_name(std::size_t index, std::size_t count) {
  const std::size_t width = std::to_string(count > 0 ? count - 1 : 0).size();
  const std::string digits = std::to_string(index);
  return "member-" + std::string(width > digits.size() ? width - digits.size() : 0, '0') + digits;
}

ProductsAccumulator::ProductsAccumulator(std::size_t cells, std::vector<double> thresholds_m)
    : thresholds_m_(std::move(thresholds_m)),
      count_(thresholds_m_.size(), std::vector<double>(cells, 0.0)),
      sum_(cells, 0.0),
      largest_(cells, 0.0),
      has_data_(cells, 0) {}

void ProductsAccumulator::add(std::span<const double> max_depth) {
  if (max_depth.size() != sum_.size()) {
    throw std::invalid_argument("ensemble::ProductsAccumulator: a member's map has " +
                                std::to_string(max_depth.size()) + " cells, not " +
                                std::to_string(sum_.size()));
  }
  for (std::size_t c = 0; c < sum_.size(); ++c) {
    const double d = max_depth[c];
    if (std::isnan(d)) continue;
    has_data_[c] = 1;
    sum_[c] += d;
    largest_[c] = std::max(largest_[c], d);
    for (std::size_t j = 0; j < thresholds_m_.size(); ++j) {
      if (d > thresholds_m_[j]) count_[j][c] += 1.0;
    }
  }
  ++members_;
}

Products ProductsAccumulator::finish() const {
  if (members_ == 0) throw std::invalid_argument("ensemble::ProductsAccumulator: no members");
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const std::size_t cells = sum_.size();
  Products p;
  p.thresholds_m = thresholds_m_;
  p.members = members_;
  p.exceedance_count = count_;
  p.exceedance_probability.assign(thresholds_m_.size(), std::vector<double>(cells, kNaN));
  p.mean_max_depth.assign(cells, kNaN);
  p.max_depth_envelope.assign(cells, kNaN);
  const auto n = static_cast<double>(members_);
  for (std::size_t c = 0; c < cells; ++c) {
    if (has_data_[c] == 0) {
      for (auto& count : p.exceedance_count) count[c] = kNaN;
      continue;
    }
    p.mean_max_depth[c] = sum_[c] / n;
    p.max_depth_envelope[c] = largest_[c];
    for (std::size_t j = 0; j < thresholds_m_.size(); ++j) {
      p.exceedance_probability[j][c] = count_[j][c] / n;
    }
  }
  return p;
}

Products combine(std::span<const std::vector<double>> max_depths,
                 const std::vector<double>& thresholds_m) {
  if (max_depths.empty()) throw std::invalid_argument("ensemble::combine: no members");
  ProductsAccumulator accumulator(max_depths.front().size(), thresholds_m);
  for (const auto& map : max_depths) accumulator.add(map);
  return accumulator.finish();
}

std::string distribution_name(Distribution distribution) {
  return distribution == Distribution::log_uniform ? "log_uniform" : "uniform";
}

std::string sampling_name(Sampling sampling) {
  return sampling == Sampling::random ? "random" : "latin_hypercube";
}

}  // namespace swemps::ensemble
