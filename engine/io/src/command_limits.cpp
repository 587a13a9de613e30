// The limits of one command (command_limits.hpp).
#include "fixstep/io/command_limits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <fixstep/core/components.hpp>
#include <fixstep/core/world.hpp>
#include <string>

namespace fixstep {

void check_command_work(std::uint64_t ticks, std::uint64_t work_per_tick, std::string_view what) {
  if (ticks > max_command_ticks) {
    throw LimitError(fmt::format("{}: {} ticks; a command may step at most {:.0e} ticks", what,
                                 ticks, double(max_command_ticks)));
  }
  if (work_per_tick > 0 && ticks > max_command_work / work_per_tick) {
    throw LimitError(fmt::format(
        "{}: {} ticks × {} body-substeps per tick = {:.3g} body-substeps; a command may do at "
        "most {:.0e} (about a day of CPU): step fewer ticks or a smaller world",
        what, ticks, work_per_tick, double(ticks) * double(work_per_tick),
        double(max_command_work)));
  }
}

void check_sync_test_memory(const World& world, int rollback) {
  const std::uint64_t bytes =
      (static_cast<std::uint64_t>(rollback) + 1) * (world.snapshot_bytes() + sizeof(World));
  if (bytes > max_sync_test_bytes) {
    throw LimitError(fmt::format(
        "--sync-test {}: {} snapshots of this world take about {:.3g} GiB; at most {:.3g} GiB "
        "allowed: roll back fewer ticks",
        rollback, rollback + 1, double(bytes) / double(std::uint64_t{1} << 30),
        double(max_sync_test_bytes) / double(std::uint64_t{1} << 30)));
  }
}

namespace {

/// Per item of a definition, what a World holds once it has stepped, bytes (its state and
/// scratch arrays; a link's gather and flows; a disc's broadphase boxes, candidate pairs and
/// contact lists with [contacts]). Measured on grids of 3·10^5 bodies (resident memory of the
/// world after two ticks): 323 bytes a body, 185 a link, 1540 more a disc.
constexpr std::uint64_t world_body_bytes = 360, world_link_bytes = 200, world_disc_bytes = 1600,
                        world_plane_bytes = 256, world_segment_bytes = 1024;
/// What building a World takes beside it while World(def) runs (the stability guard's vectors,
/// the links' colouring): measured 70 bytes a body and 260 a link more at the peak.
constexpr std::uint64_t build_body_bytes = 100, build_link_bytes = 300;
/// Per item, what a WorldDef holds, by its vectors' capacity (sizeof BodyDef is 344 bytes,
/// LinkDef 40, PlaneDef 40, SegmentDef 104 on x86-64).
constexpr std::uint64_t def_body_bytes = 360, def_link_bytes = 48, def_plane_bytes = 48,
                        def_segment_bytes = 112;
/// Per body and link, a Renderer's frame data (positions, radii, colours, trail settings), its
/// trail (48 samples of x, y and tick: 576 bytes and its bookkeeping) and its draw lists; per
/// link its ends. Fitted to `render` and `compare` of 10^5..4·10^5 bodies: about 1300 a body.
constexpr std::uint64_t render_body_bytes = 1400, render_link_bytes = 48;
/// A frame's buffers in a Renderer: OSMesa's colour and depth buffers, the pixels read back, the
/// HUD's layer.
constexpr std::uint64_t render_buffers = 4;

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

std::uint64_t discs_of(const WorldDef& def) {
  if (!def.settings.contacts) return 0;
  std::uint64_t n = 0;
  for (const BodyDef& b : def.bodies) n += b.collider.has_value() ? 1 : 0;
  return n;
}

std::uint64_t names_bytes(const WorldDef& def) {
  const std::size_t in_place = std::string().capacity();  // the short-string buffer
  std::uint64_t n = 0;
  for (const BodyDef& b : def.bodies) n += b.name.size() > in_place ? b.name.size() + 1 : 0;
  return n;
}

double gib(std::uint64_t bytes) {
  return double(bytes) / double(std::uint64_t{1} << 30);
}

}  // namespace

std::uint64_t world_bytes_estimate(const WorldDef& def) {
  return def.bodies.size() * world_body_bytes + def.links.size() * world_link_bytes +
         discs_of(def) * world_disc_bytes + def.planes.size() * world_plane_bytes +
         def.segments.size() * world_segment_bytes + names_bytes(def);
}

std::uint64_t world_build_bytes_estimate(const WorldDef& def) {
  return def.bodies.size() * build_body_bytes + def.links.size() * build_link_bytes;
}

std::uint64_t definition_bytes_estimate(const WorldDef& def) {
  return def.bodies.capacity() * def_body_bytes + def.links.capacity() * def_link_bytes +
         def.planes.capacity() * def_plane_bytes + def.segments.capacity() * def_segment_bytes +
         names_bytes(def);
}

std::uint64_t frame_bytes(int width, int height) {
  return std::uint64_t(std::max(width, 0)) * std::uint64_t(std::max(height, 0)) * 4;
}

std::uint64_t renderer_bytes_estimate(const WorldDef& def, int width, int height) {
  return def.bodies.size() * render_body_bytes + def.links.size() * render_link_bytes +
         render_buffers * frame_bytes(width, height);
}

std::uint64_t total_bytes(std::span<const MemoryTerm> terms) {
  std::uint64_t sum = 0;
  for (const MemoryTerm& t : terms) sum = saturating_add(sum, t.bytes);
  return sum;
}

void check_command_memory(std::string_view command, std::span<const MemoryTerm> terms) {
  const std::uint64_t sum = total_bytes(terms);
  if (sum <= max_command_bytes || terms.empty()) return;
  const MemoryTerm* largest = &terms.front();
  std::string parts;
  for (const MemoryTerm& t : terms) {
    if (t.bytes > largest->bytes) largest = &t;
    if (t.bytes < (std::uint64_t{1} << 20)) continue;  // the parts that matter
    parts += fmt::format("{}{} {:.2f} GiB", parts.empty() ? "" : " + ", t.what, gib(t.bytes));
  }
  throw LimitError(fmt::format(
      "{}: would need about {:.2f} GiB of memory ({}); a command may use at most {:.0f} GiB "
      "(max_command_bytes): {} dominates: {}",
      command, gib(sum), parts, gib(max_command_bytes), largest->what, largest->way_out));
}

}  // namespace fixstep
