#include "starting_surface.hpp"

#include <cmath>
#include <string>

#include "json_reading.hpp"

namespace swemps::scenario {

using json_reading::fmt;

namespace {

// A raster's value at (x, y), or 0 off the raster and on its nodata: the rasters describe a
// disturbance, and where they say nothing there is none.
double sample_or_zero(const terrain::GriddedField* field, double x_m, double y_m) {
  if (field == nullptr || !field->covers(x_m, y_m)) return 0.0;
  const double value = field->sample(x_m, y_m);
  return std::isnan(value) ? 0.0 : value;
}

// The still depth under a solitary wave's crest: as given, or the body's own there.
double still_depth_under_crest(const WaterBody& body, const SolitaryWaveStart& wave,
                               const Terrain& terrain) {
  if (wave.still_depth_m) return *wave.still_depth_m;
  if (const auto* uniform = std::get_if<UniformDepth>(&body.depth)) return uniform->depth_m;
  const auto& level = std::get<LevelSurface>(body.depth);
  // Over the floor before a rupture, as the still water's depth is measured.
  const swe::BedSource* still =
      terrain.fault_source ? terrain.bed_before_rupture.get() : terrain.bed.get();
  const double bed = still ? still->elevation(wave.crest_m[0], wave.crest_m[1]) : 0.0;
  return level.surface_elevation_m - bed;
}

}  // namespace

StartingSurface::StartingSurface(const Scenario& scene, const Terrain& terrain, std::size_t index) {
  const WaterBody& body = scene.water[index];
  uniform_velocity_m_s_ = body.velocity_m_s;
  if (index < terrain.displacement.size()) displacement_ = terrain.displacement[index];
  if (index < terrain.velocity_u.size()) u_ = terrain.velocity_u[index];
  if (index < terrain.velocity_v.size()) v_ = terrain.velocity_v[index];
  const auto* spec = std::get_if<SolitaryWaveStart>(&body.displacement);
  if (spec == nullptr) return;
  const double depth = still_depth_under_crest(body, *spec, terrain);
  if (!(depth > spec->height_m)) {
    const std::string path = "/water/" + std::to_string(index) + "/solitary_wave";
    const std::string found = "still water " + fmt(depth) + " m deep under the crest point, " +
                              "for a wave " + fmt(spec->height_m) + " m high";
    throw ScenarioError(path, found,
                        "a crest over water deeper than the wave is high, or a \"depth\" giving "
                        "the still depth the wave's shape is set by");
  }
  wave_.emplace(tsunami::SolitaryWaveSpec{spec->height_m, depth, spec->crest_m, spec->direction},
                scene.numerics.gravity_m_s2);
}

double StartingSurface::rise(double x_m, double y_m) const {
  if (wave_) return wave_->elevation(x_m, y_m);
  return sample_or_zero(displacement_.get(), x_m, y_m);
}

std::array<double, 2> StartingSurface::velocity(double x_m, double y_m) const {
  std::array<double, 2> v = uniform_velocity_m_s_;
  if (u_ || v_) v = {sample_or_zero(u_.get(), x_m, y_m), sample_or_zero(v_.get(), x_m, y_m)};
  if (wave_) {
    const auto wave = wave_->velocity(x_m, y_m);
    v = {v[0] + wave[0], v[1] + wave[1]};
  }
  return v;
}

}  // namespace swemps::scenario
