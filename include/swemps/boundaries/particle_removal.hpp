#pragma once
// What every effect that lets water leave does once it knows which particles go: remove them
// and book their volume, so that the volume balance stays closed.

#include <cstddef>
#include <cstdint>
#include <span>

#include "swemps/particles/swe_particles.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::boundaries {

struct Removal {
  std::size_t particles = 0;
  double volume_m3 = 0.0;
};

// Removes the fluid particles flagged non-zero (no ghosts allowed) and adds their volume to
// ledger.removed_m3. The volume is summed in index order, so it does not depend on the number
// of threads that flagged them.
Removal remove_flagged(particles::SweParticles& p, std::span<const std::uint8_t> flagged,
                       swe::VolumeLedger& ledger);

}  // namespace swemps::boundaries
