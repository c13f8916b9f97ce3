#pragma once
// A sea boundary: a straight line where the water goes on beyond the domain. Waves leave
// through it (an open boundary), or its water level follows a series (a tide, a wave paddle's
// record) and then, once the series ends, lets waves leave (docs/tsunami.md, "Sea
// boundaries").
//
// The boundary speaks to the water through the characteristics of the shallow-water equations
// normal to it (method.md section 1; Vacondio et al., J. Hydraul. Eng. 2012, for particles).
// With u_n the velocity along the outward normal and c = sqrt(g h), the invariant
// R_out = u_n + 2c travels out of the domain and is taken from the water beside the line; the
// other, R_in = u_n - 2c, travels in and is what the boundary sets:
//  - open: the sea at rest beyond the line, R_in = -2 sqrt(g h_0), h_0 the depth of the still
//    level; then c_b = (R_out - R_in) / 4 and u_nb = (R_out + R_in) / 2. A simple wave leaving
//    (u_n = 2(c - c_0)) gives h_b = h, u_nb = u_n: the boundary adds nothing;
//  - level: h_b = level(t) - z_b and u_nb = R_out - 2 c_b, the velocity the outgoing
//    characteristic allows at that level;
//  - water leaving faster than its waves (u_n >= c): both characteristics leave, h_b = h and
//    u_nb = u_n.
// The line is cut into stretches about a spacing long; each takes the mean boundary state of
// the fluid particles within two spacings of it, the nearer weighing more.
//
// The state reaches the water through a buffer: particles beyond the line, as deep as the
// particles' search reach, that take part in the depth sums and the force as ghosts do but
// are moved by the boundary, not by the equations (Vacondio et al.'s buffer zone). Each
// stretch's buffer moves with its u_nb and holds its depth h_b: a buffer particle carries
// h_b times the area it was made with. A fluid particle that crosses the line joins the
// buffer where it is (its volume booked as removed), so a wave leaving meets the water it
// would have met; a buffer particle the flow carries into the domain becomes a fluid particle
// (its volume booked as added); the buffer is topped up at its outer edge, a row at a time,
// and loses what drifts past it. Where the line ends on a wall, the buffer's mirror image
// across the wall fills the corner, as a wall corner's ghosts do.
//
// Everything a step reads is fixed once a step, in the topology stage, from the state the
// step began with: the buffer and the states its ghosts hold. A restored run builds the same
// ghosts from the same saved buffer.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "swemps/swe/bed.hpp"
#include "swemps/swe/effect.hpp"

namespace swemps::boundaries {

// A water level (m) given at points (t s, level m), linear between them, held at the first
// level before the first time.
class LevelSeries {
 public:
  // Throws std::invalid_argument for no points, a non-finite value, or a time not after the
  // one before, naming the point.
  explicit LevelSeries(std::vector<std::array<double, 2>> points);
  double level(double t_s) const;
  double end_time() const { return points_.back()[0]; }
  double last_level() const { return points_.back()[1]; }
  std::span<const std::array<double, 2>> points() const { return points_; }

 private:
  std::vector<std::array<double, 2>> points_;
};

struct SeaBoundarySettings {
  std::string name = "sea";         // for reports
  std::uint32_t label = 0;          // the provenance label of its water (docs/provenance.md)
  std::array<double, 2> from{};     // m: the line
  std::array<double, 2> to{};       // m
  std::array<double, 2> outward{};  // normal to the line, out of the domain; any length
  double spacing_m = 0.0;           // of the particles it lets in
  // Open: the level of the sea at rest beyond the line (m). A level boundary is open about
  // its series' last level once the series ends.
  double still_level_m = 0.0;
  std::optional<LevelSeries> level;  // set: a level boundary
  // Whether a wall meets the line at `from` and at `to`: the buffer is mirrored there.
  std::array<bool, 2> walled_ends{false, false};
  std::shared_ptr<const swe::BedSource> bed;  // z_b of new particles; null: z_b = 0
};

class SeaBoundary final : public swe::Effect {
 public:
  // Throws std::invalid_argument for a line of zero or non-finite length, an outward
  // direction that is zero or not normal to the line, a spacing that is not a positive number,
  // a still level that is not finite, or an empty name.
  explicit SeaBoundary(SeaBoundarySettings settings);

  std::string_view name() const override { return settings_.name; }
  swe::Stage stage() const override { return swe::Stage::topology; }
  bool adds_ghosts() const override { return true; }
  void add_ghosts(particles::SweParticles& p, double reach_m, const swe::Settings& settings,
                  double time_s) override;
  void set_ghost_fields(particles::SweParticles& p) override;
  void apply(swe::StepContext& context) override;
  std::string report() const override;
  void save_state(swe::StateWriter& out) const override;
  void restore_state(swe::StateReader& in) override;

  // The level the boundary holds at t: the series', or the still level (an open boundary, or
  // a level boundary whose series has ended).
  double boundary_level(double time_s) const;
  std::size_t stretch_count() const { return stretches_.size(); }
  std::size_t buffer_count() const { return buffer_.size(); }
  double volume_added() const { return added_m3_; }      // m^3, booked in the ledger
  double volume_removed() const { return removed_m3_; }  // m^3, booked in the ledger
  std::size_t particles_added() const { return particles_added_; }
  std::size_t particles_removed() const { return particles_removed_; }

 private:
  struct State {
    double depth = 0.0, normal_speed = 0.0, tangential_speed = 0.0;  // h_b; u_nb > 0 outwards
  };
  struct Stretch {
    State held;           // what its buffer holds this step
    State measured;       // from the fluid beside it at the last refresh
    bool beside = false;  // whether any fluid particle was beside it then
  };
  struct BufferParticle {
    double x, y;     // m
    double area_m2;  // its cell on the boundary's lattice, or its summed area as it left
    bool made;       // made on the boundary's lattice, not water that left the domain
  };
  // Signed distance of a point from the line (m, > 0 inside the domain) and how far along the
  // line its foot lies (m).
  std::array<double, 2> place(double x, double y) const;
  std::size_t stretch_at(double along_m) const;  // the stretch of a point along the line
  // The boundary state the characteristics give beside fluid particle i.
  State boundary_state(const particles::SweParticles& p, std::size_t i) const;
  // The depth water at `level` over `bed`, seeded as depth x cell, sums to under the
  // conservative scheme; and that of the boundary's level at a point.
  double summed_depth(double level_m, double bed_m) const;
  double still_depth(double x, double y, double time_s) const;
  std::array<double, 2> velocity(const State& s) const;
  void fill_buffer();
  // The area a buffer particle's depth sum would give: its volume is h_b times this.
  double summed_area(const BufferParticle& b) const;
  // A ghost of this refresh: the buffer particle it stands for and the stretch whose state
  // it holds.
  struct BufferGhost {
    std::uint32_t buffer, stretch;
  };
  void add_ghost_of(particles::SweParticles& p, std::uint32_t source, BufferGhost ghost, double x,
                    double y, double u, double v);

  SeaBoundarySettings settings_;
  std::array<double, 2> outward_{}, along_{};
  double length_m_ = 0.0, width_m_ = 0.0;  // the line's, a stretch's
  double gravity_m_s2_ = 9.81, time_s_ = 0.0;
  double layer_m_ = 0.0;        // how deep the buffer is: whole spacings, at least the reach
  double lattice_ratio_ = 0.0;  // a square lattice's summed area over its cell (0: not yet)
  std::vector<Stretch> stretches_;
  std::vector<BufferParticle> buffer_;
  bool filled_ = false;  // the first buffer made
  // This refresh's ghosts, from first_ghost_ on in the particle set.
  std::vector<BufferGhost> ghosts_;
  std::size_t first_ghost_ = 0;
  std::vector<std::uint8_t> beyond_;
  double added_m3_ = 0.0, removed_m3_ = 0.0;
  std::size_t particles_added_ = 0, particles_removed_ = 0;
};

}  // namespace swemps::boundaries
