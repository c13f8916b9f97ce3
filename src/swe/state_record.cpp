#include "swemps/swe/state_record.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace swemps::swe {

void StateWriter::raw(const void* data, std::size_t size) {
  const auto* begin = static_cast<const std::byte*>(data);
  bytes_.insert(bytes_.end(), begin, begin + size);
}

void StateWriter::number(double value) { raw(&value, sizeof value); }

void StateWriter::count(std::uint64_t value) { raw(&value, sizeof value); }

void StateWriter::text(std::string_view value) {
  count(value.size());
  raw(value.data(), value.size());
}

void StateWriter::numbers(std::span<const double> values) {
  count(values.size());
  raw(values.data(), values.size_bytes());
}

void StateWriter::bytes(std::span<const std::byte> values) {
  count(values.size());
  raw(values.data(), values.size());
}

StateReader::StateReader(std::span<const std::byte> bytes, std::string what)
    : bytes_(bytes), what_(std::move(what)) {}

void StateReader::raw(void* data, std::size_t size) {
  if (size > bytes_.size() - offset_) {
    throw StateError(what_ + " ends early (" + std::to_string(bytes_.size()) +
                     " bytes, more expected at byte " + std::to_string(offset_) + ")");
  }
  std::memcpy(data, bytes_.data() + offset_, size);
  offset_ += size;
}

// A length read from the record, checked against what is left before anything is allocated:
// a damaged length must give an error, not an attempt to allocate exabytes.
std::uint64_t StateReader::length(std::size_t element_size) {
  const std::uint64_t n = count();
  if (n > (bytes_.size() - offset_) / element_size) {
    throw StateError(what_ + " is damaged: a length of " + std::to_string(n) + " at byte " +
                     std::to_string(offset_ - sizeof n) + " runs past its end");
  }
  return n;
}

double StateReader::number() {
  double value = 0.0;
  raw(&value, sizeof value);
  return value;
}

std::uint64_t StateReader::count() {
  std::uint64_t value = 0;
  raw(&value, sizeof value);
  return value;
}

std::string StateReader::text() {
  std::string value(length(1), '\0');
  raw(value.data(), value.size());
  return value;
}

std::vector<double> StateReader::numbers() {
  std::vector<double> values(length(sizeof(double)));
  raw(values.data(), values.size() * sizeof(double));
  return values;
}

std::span<const std::byte> StateReader::bytes() {
  const std::uint64_t n = length(1);
  const auto values = bytes_.subspan(offset_, n);
  offset_ += n;
  return values;
}

void StateReader::expect(std::string_view label) {
  const std::size_t at = offset_;
  std::string found;
  try {
    found = text();
  } catch (const StateError&) {
    // A length that runs past the end: not a label at all.
  }
  if (found != label) {
    // Whatever stands there may be binary: quoted only when it reads as a short label.
    const bool readable =
        !found.empty() && found.size() <= 64 && std::all_of(found.begin(), found.end(), [](char c) {
          return std::isprint(static_cast<unsigned char>(c)) != 0;
        });
    throw StateError(what_ + " is not what was expected: '" + std::string(label) +
                     "' expected at byte " + std::to_string(at) + ", found " +
                     (readable ? "'" + found + "'" : std::string("something else")));
  }
}

void StateReader::expect_end() const {
  if (offset_ != bytes_.size()) {
    throw StateError(what_ + " has " + std::to_string(bytes_.size() - offset_) +
                     " bytes more than expected");
  }
}

}  // namespace swemps::swe
