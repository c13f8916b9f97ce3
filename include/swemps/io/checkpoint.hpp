#pragma once
// Checkpoint files: what a shallow-water run needs to go on later exactly where it stopped.
//
// Layout (native byte order, which the header records):
//   8 bytes   magic "SWEMPSCK"
//   u32       format version (kCheckpointVersion)
//   u32       0x01020304 as written, to refuse a file from a machine of the other byte order
//   u64       hash of the scenario file's text (content_hash): the scene the run was built from
//   u64       length of the payload in bytes
//   u64       content_hash of the payload, to refuse a damaged file
//   payload   a state record (swe/state_record.hpp): the program version, time, step count, the
//             simulation's state (swe::Simulation::save_state) and the run's own (where its
//             output stands).
// Written to <path>.partial, flushed to disk and renamed, so that a checkpoint with the final
// name is always whole, even after a crash while writing it.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace swemps::io {

// Version 2: the volume ledger books rain apart from inflow.
inline constexpr std::uint32_t kCheckpointVersion = 2;

// A checkpoint that cannot be used: missing, not a checkpoint, damaged, of another version or
// another scene.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Checkpoint {
  std::uint64_t scenario_hash = 0;
  std::string program;  // "swe-mps 0.1.0": the version that wrote it
  double time_s = 0.0;
  std::uint64_t steps = 0;
  std::vector<std::byte> simulation;  // swe::Simulation::save_state()
  std::vector<std::byte> run;         // the run's output position, flood statistics ...
};

// 64-bit FNV-1a over 8-byte words (then the remaining bytes): a fingerprint, not a defence
// against tampering; eight times faster than byte by byte, which matters at 100 MB.
std::uint64_t content_hash(std::span<const std::byte> bytes);

// content_hash of a file's bytes. Throws CheckpointError if it cannot be read.
std::uint64_t file_hash(const std::filesystem::path& file);

// Throws std::runtime_error naming the file if it cannot be written.
void write_checkpoint(const std::filesystem::path& path, const Checkpoint& checkpoint);

// Throws CheckpointError naming the file and what is wrong with it.
Checkpoint read_checkpoint(const std::filesystem::path& path);

}  // namespace swemps::io
