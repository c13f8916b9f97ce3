#include "swemps/io/checkpoint.hpp"

#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "swemps/swe/state_record.hpp"

namespace swemps::io {

namespace {

constexpr std::array<char, 8> kMagic{'S', 'W', 'E', 'M', 'P', 'S', 'C', 'K'};
constexpr std::uint32_t kByteOrderMark = 0x01020304;
constexpr const char* kPayloadLabel = "swe-mps checkpoint";

struct Header {
  std::array<char, 8> magic;
  std::uint32_t version;
  std::uint32_t byte_order;
  std::uint64_t scenario_hash;
  std::uint64_t payload_bytes;
  std::uint64_t payload_hash;
};
static_assert(sizeof(Header) == 40, "the header is written as it lies in memory");

std::string quoted(const std::filesystem::path& p) {
  // Appended piecewise: `"'" + string` trips a false -Wrestrict warning in GCC 12.
  std::string text(1, '\'');
  text += p.string();
  text += '\'';
  return text;
}

std::vector<std::byte> read_all(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::error_code ec;
    const bool exists = std::filesystem::exists(file, ec);
    throw CheckpointError("cannot read the checkpoint " + quoted(file) +
                          (exists ? "" : ": no such file"));
  }
  std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw CheckpointError("cannot read the checkpoint " + quoted(file));
  std::vector<std::byte> bytes(chars.size());
  std::memcpy(bytes.data(), chars.data(), chars.size());
  return bytes;
}

}  // namespace

std::uint64_t content_hash(std::span<const std::byte> bytes) {
  constexpr std::uint64_t kPrime = 0x100000001b3ULL;
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  const std::size_t words = bytes.size() / 8;
  for (std::size_t k = 0; k < words; ++k) {
    std::uint64_t word = 0;
    std::memcpy(&word, bytes.data() + 8 * k, 8);
    hash = (hash ^ word) * kPrime;
  }
  for (std::size_t k = 8 * words; k < bytes.size(); ++k) {
    hash = (hash ^ static_cast<std::uint64_t>(bytes[k])) * kPrime;
  }
  return hash;
}

std::uint64_t file_hash(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CheckpointError("cannot read the scenario " + quoted(file) + " to fingerprint it");
  std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return content_hash(std::as_bytes(std::span<const char>(chars)));
}

void write_checkpoint(const std::filesystem::path& path, const Checkpoint& checkpoint) {
  swe::StateWriter payload;
  payload.text(kPayloadLabel);
  payload.text(checkpoint.program);
  payload.number(checkpoint.time_s);
  payload.count(checkpoint.steps);
  payload.bytes(checkpoint.simulation);
  payload.bytes(checkpoint.run);
  const Header header{kMagic,         kCheckpointVersion,
                      kByteOrderMark, checkpoint.scenario_hash,
                      payload.size(), content_hash(payload.bytes())};

  std::filesystem::path partial = path;
  partial += ".partial";
  errno = 0;
  std::FILE* file = std::fopen(partial.c_str(), "wb");
  if (file == nullptr) {
    throw std::runtime_error("cannot create the checkpoint " + quoted(partial) + ": " +
                             (errno != 0 ? std::strerror(errno) : "unknown reason"));
  }
  const bool written =
      std::fwrite(&header, sizeof header, 1, file) == 1 &&
      std::fwrite(payload.bytes().data(), 1, payload.size(), file) == payload.size() &&
      std::fflush(file) == 0 && ::fsync(::fileno(file)) == 0;
  const int saved_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw std::runtime_error("cannot write the checkpoint " + quoted(partial) + ": " +
                             std::strerror(saved_errno != 0 ? saved_errno : EIO));
  }
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    throw std::runtime_error("cannot rename " + quoted(partial) + " to " + quoted(path) + ": " +
                             ec.message());
  }
}

Checkpoint read_checkpoint(const std::filesystem::path& path) {
  const std::vector<std::byte> bytes = read_all(path);
  const std::string what = "the checkpoint " + quoted(path);
  Header header{};
  if (bytes.size() < sizeof header) {
    throw CheckpointError(what + " is not a swe-mps checkpoint (" + std::to_string(bytes.size()) +
                          " bytes, too short)");
  }
  std::memcpy(&header, bytes.data(), sizeof header);
  if (header.magic != kMagic) throw CheckpointError(what + " is not a swe-mps checkpoint");
  if (header.byte_order != kByteOrderMark) {
    throw CheckpointError(what + " was written on a machine of another byte order");
  }
  if (header.version != kCheckpointVersion) {
    throw CheckpointError(what + " has format version " + std::to_string(header.version) +
                          "; this swe-mps reads version " + std::to_string(kCheckpointVersion));
  }
  const auto payload = std::span<const std::byte>(bytes).subspan(sizeof header);
  if (header.payload_bytes != payload.size()) {
    throw CheckpointError(what + " is damaged or cut short: " + std::to_string(payload.size()) +
                          " bytes after the header, " + std::to_string(header.payload_bytes) +
                          " expected");
  }
  if (content_hash(payload) != header.payload_hash) {
    throw CheckpointError(what + " is damaged: its contents do not match their checksum");
  }
  try {
    swe::StateReader in(payload, what);
    in.expect(kPayloadLabel);
    Checkpoint checkpoint;
    checkpoint.scenario_hash = header.scenario_hash;
    checkpoint.program = in.text();
    checkpoint.time_s = in.number();
    checkpoint.steps = in.count();
    const auto simulation = in.bytes();
    checkpoint.simulation.assign(simulation.begin(), simulation.end());
    const auto run = in.bytes();
    checkpoint.run.assign(run.begin(), run.end());
    in.expect_end();
    return checkpoint;
  } catch (const swe::StateError& e) {
    throw CheckpointError(e.what());
  }
}

}  // namespace swemps::io
