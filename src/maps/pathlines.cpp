#include "swemps/maps/pathlines.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace swemps::maps {

namespace {

// The label holding the largest share of particle i's water (the first of equal ones).
std::uint32_t largest_share(const particles::SweParticles& p, std::size_t i) {
  const std::size_t labels = p.label_count();
  const double* shares = p.label_share.data() + i * labels;
  return static_cast<std::uint32_t>(std::max_element(shares, shares + labels) - shares);
}

// Reads the numbers state() wrote, one at a time, refusing a record that ends too soon.
class Numbers {
 public:
  explicit Numbers(std::span<const double> values) : values_(values) {}
  double next() {
    if (at_ >= values_.size()) throw std::invalid_argument("the pathlines' record ends too soon");
    return values_[at_++];
  }
  std::size_t next_count(double most) {
    const double n = next();
    if (!(n >= 0.0 && n <= most) || n != std::floor(n)) {
      throw std::invalid_argument("the pathlines' record is damaged");
    }
    return static_cast<std::size_t>(n);
  }
  bool done() const { return at_ == values_.size(); }

 private:
  std::span<const double> values_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<std::uint32_t> choose_pathline_particles(const particles::SweParticles& p,
                                                     const PathlineChoice& choice) {
  if (choice.label && *choice.label >= p.label_count()) {
    throw std::invalid_argument("choose_pathline_particles: the particles carry no label " +
                                std::to_string(*choice.label));
  }
  std::vector<std::uint32_t> passing;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    // At least half, so that a particle counts for one source at most (but for one of two
    // equal halves, both).
    if (choice.label && p.label_share[i * p.label_count() + *choice.label] < 0.5) continue;
    if (choice.area && !choice.area->contains(p.x[i], p.y[i])) continue;
    passing.push_back(static_cast<std::uint32_t>(i));
  }
  if (passing.size() <= choice.count) return passing;
  std::vector<std::uint32_t> chosen(choice.count);
  for (std::size_t k = 0; k < choice.count; ++k) {
    chosen[k] = passing[k * passing.size() / choice.count];
  }
  return chosen;
}

void PathlineRecorder::start(const particles::SweParticles& p,
                             std::span<const std::uint32_t> chosen, double time_s) {
  if (started_) throw std::logic_error("PathlineRecorder::start: started already");
  lines_.assign(chosen.size(), Pathline{});
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const std::size_t i = chosen[k];
    if (i >= p.fluid_count()) {
      throw std::out_of_range("PathlineRecorder::start: no fluid particle " + std::to_string(i));
    }
    Pathline& line = lines_[k];
    line.x.push_back(p.x[i]);
    line.y.push_back(p.y[i]);
    line.t.push_back(time_s);
    if (p.label_count() > 0) line.label = largest_share(p, i);
  }
  started_ = true;
  last_time_s_ = time_s;
}

void PathlineRecorder::record(const particles::SweParticles& p, double time_s) {
  if (!started_ || !(time_s > last_time_s_) || !p.tracks_pathlines()) return;
  for (std::size_t i = 0; i < p.fluid_count(); ++i) {
    const std::int32_t index = p.pathline[i];
    if (index == particles::kNoPathline) continue;
    if (static_cast<std::size_t>(index) >= lines_.size()) {
      throw std::logic_error("PathlineRecorder::record: particle " + std::to_string(i) +
                             " carries pathline " + std::to_string(index) + " of " +
                             std::to_string(lines_.size()));
    }
    Pathline& line = lines_[static_cast<std::size_t>(index)];
    if (line.fate != Pathline::Fate::in_domain) continue;
    line.x.push_back(p.x[i]);
    line.y.push_back(p.y[i]);
    line.t.push_back(time_s);
  }
  last_time_s_ = time_s;
}

void PathlineRecorder::end(std::span<const particles::PathlineEnd> ends, double time_s) {
  for (const auto& e : ends) {
    if (e.pathline < 0 || static_cast<std::size_t>(e.pathline) >= lines_.size()) {
      throw std::logic_error("PathlineRecorder::end: no pathline " + std::to_string(e.pathline));
    }
    Pathline& line = lines_[static_cast<std::size_t>(e.pathline)];
    if (line.fate != Pathline::Fate::in_domain) continue;
    line.x.push_back(e.x);
    line.y.push_back(e.y);
    line.t.push_back(time_s);
    line.fate = e.cause == particles::PathlineEnd::Cause::merged ? Pathline::Fate::merged
                                                                 : Pathline::Fate::left;
    if (line.fate == Pathline::Fate::merged && e.into >= 0) {
      line.merged_into = static_cast<std::uint32_t>(e.into);
    }
  }
}

std::size_t PathlineRecorder::vertices() const {
  std::size_t n = 0;
  for (const auto& line : lines_) n += line.t.size();
  return n;
}

std::vector<double> PathlineRecorder::state() const {
  std::vector<double> out{started_ ? 1.0 : 0.0, last_time_s_, static_cast<double>(lines_.size())};
  for (const auto& line : lines_) {
    out.push_back(line.label ? static_cast<double>(*line.label) : -1.0);
    out.push_back(static_cast<double>(line.fate));
    out.push_back(line.merged_into ? static_cast<double>(*line.merged_into) : -1.0);
    out.push_back(static_cast<double>(line.t.size()));
    for (const auto* field : {&line.x, &line.y, &line.t}) {
      out.insert(out.end(), field->begin(), field->end());
    }
  }
  return out;
}

void PathlineRecorder::restore(std::span<const double> state) {
  Numbers in(state);
  const bool started = in.next_count(1) == 1;
  const double last_time_s = in.next();
  std::vector<Pathline> lines(in.next_count(static_cast<double>(state.size())));
  for (auto& line : lines) {
    const double label = in.next();  // -1: none
    if (!(label >= -1.0 && label < 4294967296.0) || label != std::floor(label)) {
      throw std::invalid_argument("the pathlines' record is damaged");
    }
    if (label >= 0.0) line.label = static_cast<std::uint32_t>(label);
    line.fate = static_cast<Pathline::Fate>(in.next_count(2));
    const double into = in.next();  // -1: none
    if (!(into >= -1.0 && into < static_cast<double>(lines.size())) || into != std::floor(into)) {
      throw std::invalid_argument("the pathlines' record is damaged");
    }
    if (into >= 0.0) line.merged_into = static_cast<std::uint32_t>(into);
    const std::size_t n = in.next_count(static_cast<double>(state.size()));
    for (auto* field : {&line.x, &line.y, &line.t}) {
      for (std::size_t k = 0; k < n; ++k) field->push_back(in.next());
    }
  }
  if (!in.done()) throw std::invalid_argument("the pathlines' record is longer than its lines");
  lines_ = std::move(lines);
  started_ = started;
  last_time_s_ = last_time_s;
}

}  // namespace swemps::maps
