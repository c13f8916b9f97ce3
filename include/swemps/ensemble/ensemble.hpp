#pragma once
// An ensemble of scenes: one base scene run many times, each member with some of its values
// changed (a hydrograph's peak, a roughness, a sea level), and the members' flood maps
// combined into one probabilistic map. This module says what the members are and how their
// maps combine; it reads and writes nothing. The ensemble file is read by
// scenario::load_ensemble, which also writes each member's scene; the ensemble command runs
// the members (locally or through a scheduler) and collects their results.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace swemps::ensemble {

// How a sampled knob's values spread over its range.
enum class Distribution {
  uniform,      // evenly in the value
  log_uniform,  // evenly in its logarithm: a roughness or a return period spanning decades
};

// How the draws of the sampled knobs are made.
enum class Sampling {
  // Latin hypercube: each knob's range cut into `samples` equal strata (in probability), one
  // draw in each, the strata paired at random across knobs. Covers every range evenly even
  // for the few members an expensive flood model affords.
  latin_hypercube,
  random,  // independent draws
};

// One value of the scene that the members vary, named by a JSON pointer (RFC 6901) into the
// base scene: "/friction/manning_n", "/inflow/0/hydrograph/1/1".
struct Knob {
  std::string pointer;
  std::string name;  // the members table's column; the pointer unless the file names it
  // Listed values, each as JSON text (a number, a string, an array such as a whole
  // hydrograph). Empty for a sampled knob.
  std::vector<std::string> values;
  // A sampled knob's range, low < high (both > 0 for log_uniform).
  double low = 0.0, high = 0.0;
  Distribution distribution = Distribution::uniform;

  bool sampled() const { return values.empty(); }
};

// How a Slurm cluster runs the members: sbatch options the ensemble file (or the command line)
// sets. Each empty or absent one is left to the cluster's defaults.
struct SlurmSettings {
  std::string partition, account, qos;
  std::string time_limit;          // per member, in Slurm's notation: "30", "2:00:00", "1-00:00:00"
  std::string memory;              // per member, in Slurm's notation: "4G"
  std::optional<int> max_running;  // members running at once: the array's "%" throttle
  std::vector<std::string> extra;  // further sbatch options, verbatim ("--constraint=ib")
};

struct Ensemble {
  std::filesystem::path file;        // the ensemble file (absolute)
  std::filesystem::path base_scene;  // the scenario every member starts from (absolute)
  std::string base_scene_text;       // its text, read once, so every member starts from it
  std::vector<Knob> knobs;           // in the file's order
  // Draws of the sampled knobs; 1 when no knob is sampled.
  std::size_t samples = 1;
  std::uint64_t seed = 0;
  Sampling sampling = Sampling::latin_hypercube;
  // Depths (m) whose exceedance the products map, ascending.
  std::vector<double> thresholds_m{0.1, 0.3, 0.5, 1.0};
  int threads_per_member = 1;  // OpenMP threads of each member's run
  std::optional<int> jobs;     // local backend: members at once; absent: one per core
  // A member still running after this many seconds is stopped and recorded as "timeout".
  std::optional<double> run_time_limit_s;
  // Each member's run also writes a checkpoint every this many output times, so that a member
  // killed outright (a node lost, SIGKILL) goes on from there when run again. Absent: only
  // when a run is stopped by a signal (a scheduler's time limit, scancel).
  std::optional<int> checkpoint_every;
  // Where the members' folders and the products go (absolute).
  std::filesystem::path folder;
  SlurmSettings slurm;
};

// One member: its place in the ensemble and each knob's value, as JSON text, in knob order.
struct Member {
  std::size_t index = 0;
  std::vector<std::string> values;
};

// The number of members: the product of the listed knobs' value counts, times `samples`.
std::size_t member_count(const Ensemble& ensemble);

// Every member, in index order: the combinations of the listed knobs, the first knob varying
// slowest, and within each combination the `samples` draws of the sampled knobs, the same
// draws for every combination (so that members differing only in a listed knob are paired).
// The draws depend only on the seed, the sampling, the knobs' ranges and their order: the
// same file gives the same members on any machine and with any standard library.
std::vector<Member> members(const Ensemble& ensemble);

// One member, as members() has it, without making the others (a scheduler's task runs one).
// Throws std::out_of_range for an index past the last member.
Member member(const Ensemble& ensemble, std::size_t index);

// The sampled knobs' draws as fractions in [0, 1), draws[sample][sampled knob], before the
// ranges are applied: what members() maps through each knob's distribution.
std::vector<std::vector<double>> unit_draws(std::size_t samples, std::size_t knobs,
                                            std::uint64_t seed, Sampling sampling);

// A member's folder name: "member-07" of 15, the index zero-padded to the width of the last.
std::string member_folder_name(std::size_t index, std::size_t count);

// The products of an ensemble, each a map of ny * nx cells as the members' maps are.
struct Products {
  std::vector<double> thresholds_m;
  std::vector<std::vector<double>> exceedance_count;        // [threshold][cell]
  std::vector<std::vector<double>> exceedance_probability;  // [threshold][cell]
  std::vector<double> mean_max_depth;                       // m
  std::vector<double> max_depth_envelope;                   // m
  std::size_t members = 0;                                  // members combined
};

// Combines the members' maximum-depth maps (each ny * nx cells, NaN where the member's cell
// never had data) one at a time, so that an ensemble of thousands of members needs the memory
// of a few maps, not of all of them. A cell without data in a member counts as dry there
// (depth 0): a member's grid has data wherever its particles reached. Per cell: the members
// whose maximum depth exceeds each threshold (strictly), that count over the members, the mean
// of the maxima and their largest value. A cell with data in no member is NaN in every map.
// Members added in the same order give the same bits.
class ProductsAccumulator {
 public:
  ProductsAccumulator(std::size_t cells, std::vector<double> thresholds_m);
  // Throws std::invalid_argument for a map of another size.
  void add(std::span<const double> max_depth);
  std::size_t members() const { return members_; }
  // Throws std::invalid_argument when no member was added.
  Products finish() const;

 private:
  std::vector<double> thresholds_m_;
  std::vector<std::vector<double>> count_;  // [threshold][cell]
  std::vector<double> sum_, largest_;
  std::vector<unsigned char> has_data_;
  std::size_t members_ = 0;
};

// All maps at once, through ProductsAccumulator. Throws std::invalid_argument for no members
// or maps of different sizes.
Products combine(std::span<const std::vector<double>> max_depths,
                 const std::vector<double>& thresholds_m);

// Names for messages and tables.
std::string distribution_name(Distribution distribution);
std::string sampling_name(Sampling sampling);

}  // namespace swemps::ensemble
