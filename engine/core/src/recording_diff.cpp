// compare_recordings and diff_recordings (recording_diff.hpp): the worlds, the inputs and the
// stored hashes compared, then both recordings replayed side by side.
#include "fixstep/core/recording_diff.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/work_progress.hpp"

namespace fixstep {

namespace {

bool same_vec(Vec2 a, Vec2 b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y);
}

bool same_body_input(const BodyInput& a, const BodyInput& b) {
  return a.body == b.body && a.kind == b.kind && same_vec(a.value, b.value);
}

/// What differs in the recorded settings, e.g. "dt 0.01 against 0.02 s", or "".
std::string settings_difference(const RecordedSettings& a, const RecordedSettings& b) {
  std::vector<std::string> parts;
  if (a.integrator != b.integrator) parts.emplace_back("integrator");
  if (a.precision != b.precision) parts.emplace_back("precision");
  if (!same_bits(a.dt, b.dt)) parts.push_back(fmt::format("dt {} against {} s", a.dt, b.dt));
  if (a.substeps != b.substeps) {
    parts.push_back(fmt::format("substeps {} against {}", a.substeps, b.substeps));
  }
  if (a.damping_split != b.damping_split) parts.emplace_back("damping split");
  if (a.seeding != b.seeding) parts.emplace_back("seeding (format version)");
  return fmt::format("{}", fmt::join(parts, ", "));
}

std::string rules_text(const Recording& r) {
  return r.rules_name.empty() ? std::string("none (physics only)")
                              : fmt::format("{} version {}", r.rules_name, r.rules_version);
}

std::string world_difference(const Recording& a, const Recording& b) {
  if (a.definition_hash != b.definition_hash) {
    return fmt::format(
        "their worlds differ: definition hash {:016x} (scene {}) against {:016x} (scene {})",
        a.definition_hash, a.scene, b.definition_hash, b.scene);
  }
  if (const std::string s = settings_difference(a.settings, b.settings); !s.empty()) {
    return "their recorded settings differ: " + s;
  }
  if (a.rules_name != b.rules_name || a.rules_version != b.rules_version) {
    return fmt::format("their rules differ: {} against {}", rules_text(a), rules_text(b));
  }
  return {};
}

std::optional<std::uint64_t> first_input_difference(const Recording& a, const Recording& b,
                                                    std::uint64_t common) {
  constexpr std::uint64_t never = std::numeric_limits<std::uint64_t>::max();
  const TickInput none{};
  const TickInput* in_a = &none;
  const TickInput* in_b = &none;
  std::size_t i = 0, j = 0;
  // Inputs change only at the recordings' change ticks: only those need comparing.
  for (std::uint64_t t = 0; t < common;) {
    while (i < a.inputs.size() && a.inputs[i].tick <= t) in_a = &a.inputs[i++];
    while (j < b.inputs.size() && b.inputs[j].tick <= t) in_b = &b.inputs[j++];
    if (!same_input(*in_a, *in_b)) return t;
    t = std::min(i < a.inputs.size() ? a.inputs[i].tick : never,
                 j < b.inputs.size() ? b.inputs[j].tick : never);
  }
  return std::nullopt;
}

/// The recording's stored hashes, its final hash added at its last tick when not stored there.
std::vector<std::pair<std::uint64_t, std::uint64_t>> stored_hashes(const Recording& r) {
  auto hashes = r.hashes;
  if (hashes.empty() || hashes.back().first != r.ticks) hashes.emplace_back(r.ticks, r.final_hash);
  return hashes;
}

void compare_hashes(const Recording& a, const Recording& b, RecordingDiff& diff) {
  const auto ha = stored_hashes(a), hb = stored_hashes(b);
  std::size_t i = 0, j = 0;
  std::uint64_t last_equal = 0;
  while (i < ha.size() && j < hb.size()) {
    if (ha[i].first != hb[j].first) {
      (ha[i].first < hb[j].first ? i : j)++;
      continue;
    }
    ++diff.hashes_compared;
    if (ha[i].second != hb[j].second) {
      diff.hashes = RecordingDiff::HashDifference{ha[i].first, last_equal};
      return;
    }
    last_equal = ha[i].first, ++i, ++j;
  }
}

/// One recording replayed here: its world, rules, input and the check of its stored hashes.
struct Replayer {
  const Recording& rec;
  const TickRules& rules;
  World world;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> hashes = stored_hashes(rec);
  std::size_t next_change = 0, next_hash = 0;
  TickInput input{};
  RecordingDiff::Reproduced reproduced{};

  /// Steps tick t (the recording's input, then the rules) and checks a hash stored there.
  void step(std::uint64_t t) {
    if (next_change < rec.inputs.size() && rec.inputs[next_change].tick == t) {
      input = rec.inputs[next_change++];
    }
    input.tick = t;
    rules.tick(world, input);
    if (reproduced.mismatch || next_hash >= hashes.size() || hashes[next_hash].first != t + 1) {
      return;
    }
    const std::uint64_t actual = world.state_hash();
    if (actual != hashes[next_hash].second) {
      const std::uint64_t last = next_hash > 0 ? hashes[next_hash - 1].first : 0;
      reproduced.mismatch = ReplayReport::Mismatch{t + 1, last, hashes[next_hash].second, actual};
      return;
    }
    ++reproduced.verified, ++next_hash;
  }
};

void check_definition(const WorldDef& def, const Recording& rec, const char* which) {
  const std::uint64_t hash = definition_hash(def);
  if (hash != rec.definition_hash) {
    throw std::invalid_argument(
        fmt::format("diff_recordings: def_{} builds another world than recording {} was made with "
                    "(definition hash {:016x}, recorded {:016x})",
                    which, which, hash, rec.definition_hash));
  }
}

}  // namespace

bool same_input(const TickInput& a, const TickInput& b) {
  return same_vec(a.push, b.push) && a.held == b.held && a.pressed == b.pressed &&
         a.released == b.released && same_vec(a.pointer, b.pointer) && a.drag_body == b.drag_body &&
         std::equal(a.bodies.begin(), a.bodies.end(), b.bodies.begin(), b.bodies.end(),
                    same_body_input) &&
         std::equal(a.axes.begin(), a.axes.end(), b.axes.begin(),
                    [](double x, double y) { return same_bits(x, y); }) &&
         a.joints == b.joints;
}

RecordingDiff compare_recordings(const Recording& a, const Recording& b) {
  RecordingDiff diff;
  diff.ticks_a = a.ticks, diff.ticks_b = b.ticks;
  diff.hash_every_a = a.hash_every, diff.hash_every_b = b.hash_every;
  diff.world_difference = world_difference(a, b);
  if (!diff.world_difference.empty()) return diff;
  diff.input_tick = first_input_difference(a, b, std::min(a.ticks, b.ticks));
  compare_hashes(a, b, diff);
  return diff;
}

std::uint64_t replay_end(const RecordingDiff& diff) {
  const std::uint64_t common = std::min(diff.ticks_a, diff.ticks_b);
  if (!diff.input_tick && !diff.hashes) return common;
  std::uint64_t end = 0;
  if (diff.input_tick) end = *diff.input_tick + 1;
  if (diff.hashes) end = std::max(end, diff.hashes->tick);
  return std::min(end, common);
}

RecordingDiff diff_recordings(const WorldDef& def_a, const Recording& a, const WorldDef& def_b,
                              const Recording& b, const TickRules& rules_a,
                              const TickRules& rules_b) {
  check_definition(def_a, a, "a");
  check_definition(def_b, b, "b");
  RecordingDiff diff = compare_recordings(a, b);
  if (!diff.world_difference.empty()) return diff;
  Replayer ra{a, rules_a, World(def_a)}, rb{b, rules_b, World(def_b)};
  if (rules_a.attach) rules_a.attach(ra.world);
  if (rules_b.attach) rules_b.attach(rb.world);
  // (Not emplace(): clang does not take the nested aggregate as default-constructible there.)
  diff.replay = RecordingDiff::Replay{};
  RecordingDiff::Replay& out = *diff.replay;
  const std::uint64_t end = replay_end(diff);
  auto compare = [&] {
    out.state = first_difference(state_fields(ra.world), state_fields(rb.world));
    if (out.state) out.state_text = describe(*out.state, &ra.world);
    return out.state.has_value();
  };
  for (std::uint64_t t = 0; !compare() && t < end; ++t) {
    throw_if_stop_requested();
    ra.step(t), rb.step(t);
    out.ticks = t + 1;
    if (out.ticks % 1024 == 0) report_work_progress("diff", "tick", out.ticks, end);
  }
  out.a = ra.reproduced, out.b = rb.reproduced;
  return diff;
}

}  // namespace fixstep
