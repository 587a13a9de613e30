// The trails behind the bodies: each body's recent positions, sampled every tick and kept per
// handle (Entity), so that creating and destroying bodies in any order never joins two unrelated
// bodies' positions, and a frame drawn every K ticks shows the same trail as one drawn every tick.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fixstep/core/world.hpp"
#include "fixstep/render/frame_data.hpp"

namespace fixstep {

/// One ring of recent positions per body handle: what Renderer::draw draws behind the bodies.
///
/// Sampling. sample(world) runs after every tick (Session does); a frame drawn at a tick that
/// was not sampled (the first frame, or ticks stepped outside a Session) is sampled from the
/// frame itself by prepare(). A body's trail keeps the samples of the last trail_time seconds
/// (Appearance::trail_time), at most `capacity` of them: a trail longer than capacity ticks
/// keeps every k-th tick, k = ceil(trail_time / dt / (capacity - 1)) (10 s at dt = 1 ms: every
/// 213th tick), so memory is bounded per body whatever the trail's length or dt.
///
/// Cuts: a trail starts afresh (no line joins the old positions to the new) when
///   - its body is new: just created, or a reused slot with a new generation, or absent from the
///     last sample (destroyed and brought back by a rewind);
///   - its body was moved between ticks: where a tick starts (the world's previous position,
///     which World::set_body and set_position set as well) differs from where the tick before
///     left it by more than float rounding (a teleport, a respawn, a reload; motion of any
///     speed is never a cut);
///   - its body is hidden (Appearance::visible false) or its trail switched off (trail false)
///     at a draw, or its trail_time changed: the trail restarts where the body is when it is
///     drawn again. Visibility and trail settings are read when a frame is drawn (prepare());
///     a body new to the trails reads them from its Appearance at once.
///
/// Drawing (points()): the samples younger than trail_time before the moment the frame shows
/// (tick - (1 - alpha)), oldest first, and last the body's drawn (interpolated) position.
///
/// Cost: sample() is O(bodies) (two passes of World::interpolate_positions and one over the
/// trails), with no allocation once every slot seen has storage; memory is capacity * 12 bytes
/// per slot (576 bytes) plus 40 bytes of state.
class Trails {
 public:
  /// Most samples one trail keeps.
  static constexpr int capacity = 48;
  /// Most points points() gives: the samples and the drawn position.
  static constexpr int max_points = capacity + 1;

  /// Samples every body of `world` at its current tick (after a tick's step and rules). A world
  /// stopped by the runtime guard (World::fault()) is not sampled.
  void sample(const World& world);
  /// Before drawing `frame`: reads each body's visibility and trail time (cutting trails as
  /// described above), and samples the frame's positions as tick frame.tick if that tick was not
  /// sampled. A frame without ids (filled by hand) keys body j by the handle World(def) gives
  /// def.bodies[j]. Throws std::invalid_argument if ids, visible or trail_time is neither empty
  /// nor as long as x, an id is null or a trail time is not finite and >= 0; handles within one
  /// frame must be distinct.
  void prepare(const RenderFrame& frame);
  /// Forgets every trail: each body starts an empty one at the next sample (after a restart, a
  /// rewind or a jump of the camera).
  void clear();
  /// The trail of body j of `frame` (the frame last given to prepare()), oldest first: its
  /// points' positions (m) and ages (s before the moment the frame shows, the drawn position's
  /// 0) are written to xs, ys and ages; returns their number, 0 (hidden or no trail) to
  /// max_points. One point: the body has no past yet.
  int points(const RenderFrame& frame, std::size_t j, std::span<float, max_points> xs,
             std::span<float, max_points> ys, std::span<float, max_points> ages) const;
  /// The tick of the last sample, if any.
  [[nodiscard]] bool sampled() const { return sampled_; }
  [[nodiscard]] std::uint64_t sampled_tick() const { return sampled_tick_; }

 private:
  /// What a trail shows, from a body's Appearance.
  struct Setting {
    bool on = true;           ///< visible and trail on
    float window = 0.0f;      ///< trail_time in ticks
    std::uint32_t every = 1;  ///< ticks between kept samples
  };
  [[nodiscard]] static Setting setting(bool visible, double trail_time, double dt);
  /// Makes room for slot `slot` (new slots were never seen).
  void grow(std::uint32_t slot);
  /// Empties slot s's ring.
  void reset(std::uint32_t s) { count_[s] = 0; }
  /// One tick's sample of n bodies: id(j), its position at the start of the tick (start_x/y,
  /// or empty: unknown) and at its end (end_x/y), and setting(j) for bodies new to the trails.
  template <class IdOf, class SettingOf>
  void record(std::uint64_t tick, std::size_t n, IdOf&& id, std::span<const float> start_x,
              std::span<const float> start_y, std::span<const float> end_x,
              std::span<const float> end_y, SettingOf&& setting_of);
  [[nodiscard]] bool known(Entity e) const;

  // Per slot: the generation its trail belongs to, the sample it was last seen in, where the
  // last sampled tick left it and that tick, its setting, and the ring (head_: next write
  // position; count_: samples; x_, y_ m and t_ the sample's tick, low 32 bits).
  std::vector<std::uint32_t> generation_, seen_;
  std::vector<float> last_x_, last_y_;
  std::vector<std::uint64_t> last_tick_;
  std::vector<Setting> setting_;
  std::vector<std::uint8_t> head_, count_;
  std::vector<float> x_, y_;
  std::vector<std::uint32_t> t_;
  std::uint32_t stamp_ = 1;  ///< the last sample's number; seen_ starts at 0, never stamp_ - 1
  bool sampled_ = false;
  std::uint64_t sampled_tick_ = 0;
  std::vector<float> start_x_, start_y_, end_x_, end_y_;  ///< sample()'s scratch
};

}  // namespace fixstep
