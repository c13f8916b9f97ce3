#pragma once
// The state a shallow-water simulation carries from one step to the next, as a record of
// bytes: written by Simulation::save_state() and the effects' save_state(), read back by their
// restore_state(). Where the bytes go is the caller's business (memory, for the rollback after a
// breakdown; a checkpoint file, io/checkpoint.hpp). Numbers are stored as their bit patterns, so
// a restored simulation continues bit for bit; nothing here knows a file exists.

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace swemps::swe {

// A record that ends early, holds a wrong label, or does not fit the simulation it is
// restored into.
class StateError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateWriter {
 public:
  void number(double value);
  void count(std::uint64_t value);
  void text(std::string_view value);              // with its length
  void numbers(std::span<const double> values);   // with its length
  void bytes(std::span<const std::byte> values);  // with its length: a nested record

  std::span<const std::byte> bytes() const { return bytes_; }
  std::size_t size() const { return bytes_.size(); }
  void clear() { bytes_.clear(); }
  void reserve(std::size_t bytes) { bytes_.reserve(bytes); }

 private:
  void raw(const void* data, std::size_t size);
  std::vector<std::byte> bytes_;
};

class StateReader {
 public:
  // `what` names the record in error messages ("checkpoint 'run.checkpoint'").
  StateReader(std::span<const std::byte> bytes, std::string what);

  double number();
  std::uint64_t count();
  std::string text();
  std::vector<double> numbers();
  std::span<const std::byte> bytes();
  // Reads a text and throws StateError unless it is `label`: sections begin with one, so a
  // record read into the wrong place fails at once and says where.
  void expect(std::string_view label);
  // Throws StateError unless every byte has been read.
  void expect_end() const;

  const std::string& what() const { return what_; }

 private:
  void raw(void* data, std::size_t size);
  std::uint64_t length(std::size_t element_size);
  std::span<const std::byte> bytes_;
  std::size_t offset_ = 0;
  std::string what_;
};

}  // namespace swemps::swe
