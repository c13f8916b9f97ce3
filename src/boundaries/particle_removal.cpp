#include "swemps/boundaries/particle_removal.hpp"

namespace swemps::boundaries {

Removal remove_flagged(particles::SweParticles& p, std::span<const std::uint8_t> flagged,
                       swe::VolumeLedger& ledger) {
  Removal removal;
  for (std::size_t i = 0; i < flagged.size(); ++i) {
    if (!flagged[i]) continue;
    removal.volume_m3 += p.volume[i];
    ledger.remove_labelled(p, i);
    ++removal.particles;
  }
  if (removal.particles == 0) return removal;
  p.remove(flagged);
  ledger.removed_m3 += removal.volume_m3;
  return removal;
}

}  // namespace swemps::boundaries
