// describe(RecordingDiff) (recording_diff.hpp): a diff of two recordings as lines, ending with
// what it means.
#include <fmt/format.h>

#include "fixstep/core/recording_diff.hpp"

namespace fixstep {

namespace {

using Reproduced = RecordingDiff::Reproduced;

std::string lengths(const RecordingDiff& d, std::string_view a, std::string_view b) {
  return fmt::format("{}: {} ticks, a state hash every {}; {}: {} ticks, a state hash every {}", a,
                     d.ticks_a, d.hash_every_a, b, d.ticks_b, d.hash_every_b);
}

std::string inputs_line(const RecordingDiff& d) {
  const std::uint64_t common = std::min(d.ticks_a, d.ticks_b);
  if (!d.input_tick) return fmt::format("inputs: equal over the {} ticks both recorded", common);
  return fmt::format("inputs: first differ at tick {} (equal before it)", *d.input_tick);
}

std::string hashes_line(const RecordingDiff& d) {
  if (!d.hashes) {
    return fmt::format("stored hashes: equal at the {} ticks both stored one", d.hashes_compared);
  }
  const auto& h = *d.hashes;
  if (h.exact()) {
    return fmt::format("stored hashes: first differ at tick {} (exact: equal at tick {})", h.tick,
                       h.last_equal);
  }
  return fmt::format(
      "stored hashes: first differ at tick {}, equal at tick {}: the states first differ in "
      "ticks {} .. {}",
      h.tick, h.last_equal, h.last_equal + 1, h.tick);
}

std::string replay_line(const RecordingDiff::Replay& r) {
  if (r.state) return "replayed here: the states first differ: " + r.state_text;
  return fmt::format("replayed here: both step to identical states through tick {}", r.ticks);
}

std::string reproduced_line(std::string_view name, const Reproduced& r, std::uint64_t ticks) {
  if (!r.mismatch) {
    return fmt::format(
        "{}: its stored hashes are reproduced here ({} stored hashes through tick {})", name,
        r.verified, ticks);
  }
  const auto& m = *r.mismatch;
  return fmt::format(
      "{}: its stored hashes are not reproduced here from tick {} on (state_hash {:016x} "
      "recorded, {:016x} replayed; reproduced through tick {})",
      name, m.tick, m.expected, m.actual, m.last_match);
}

/// The desync case: equal inputs, stored hashes that differ, identical replays.
std::string desync_verdict(const RecordingDiff& d, std::string_view a, std::string_view b) {
  const auto& r = *d.replay;
  const auto& h = *d.hashes;
  const std::string when = h.exact() ? fmt::format("at tick {}", h.tick)
                                     : fmt::format("in ticks {} .. {}", h.last_equal + 1, h.tick);
  const std::string head = fmt::format(
      "the recordings' inputs are equal up to tick {}; their stored hashes first differ at tick "
      "{} ({}); replayed here both step to identical states, and ",
      h.tick, h.tick, h.exact() ? "exact" : "hashes are not stored every tick");
  if (r.a.mismatch && r.b.mismatch) {
    return head + fmt::format(
                      "neither's hashes are reproduced here: this build steps "
                      "differently from the builds that made them");
  }
  const bool a_diverged = r.a.mismatch.has_value();
  const std::string_view good = a_diverged ? b : a, bad = a_diverged ? a : b;
  return head + fmt::format(
                    "{}'s hashes are reproduced here, {}'s are not from tick {} on: the state of "
                    "{}'s peer diverged {}, not its inputs",
                    good, bad, (a_diverged ? r.a : r.b).mismatch->tick, bad, when);
}

std::string verdict(const RecordingDiff& d, std::string_view a, std::string_view b) {
  if (!d.world_difference.empty()) {
    return "verdict: " + d.world_difference + "; nothing else was compared";
  }
  if (d.identical()) {
    return fmt::format("verdict: identical: equal inputs and stored hashes over {} ticks",
                       d.ticks_a);
  }
  const std::uint64_t common = std::min(d.ticks_a, d.ticks_b);
  if (!d.input_tick && !d.hashes) {
    return fmt::format(
        "verdict: equal inputs and stored hashes over the {} ticks both recorded; "
        "{} is longer",
        common, d.ticks_a > d.ticks_b ? a : b);
  }
  if (!d.replay) {
    return fmt::format(
        "verdict: the recordings differ (their {}); the bodies need a replay with the rules "
        "they were made with: the game's own --diff",
        d.input_tick ? "inputs" : "stored hashes");
  }
  if (!d.input_tick && !d.replay->state) return "verdict: " + desync_verdict(d, a, b);
  if (d.replay->state && d.input_tick) {
    return fmt::format(
        "verdict: the inputs first differ at tick {}; replayed here the states first differ at "
        "tick {}: {}",
        *d.input_tick, d.replay->state->tick, d.replay->state_text);
  }
  if (d.replay->state) {
    return fmt::format(
        "verdict: the inputs are equal, yet replayed here the states part at tick {}: the rules or "
        "this build do not step deterministically",
        d.replay->state->tick);
  }
  return fmt::format(
      "verdict: the inputs differ at tick {}, and replayed here the states are still identical "
      "through tick {}",
      *d.input_tick, d.replay->ticks);
}

}  // namespace

std::vector<std::string> describe(const RecordingDiff& d, std::string_view a, std::string_view b) {
  std::vector<std::string> lines{lengths(d, a, b)};
  if (d.world_difference.empty()) {
    lines.push_back(inputs_line(d));
    lines.push_back(hashes_line(d));
    if (d.replay) {
      lines.push_back(replay_line(*d.replay));
      lines.push_back(reproduced_line(a, d.replay->a, d.replay->ticks));
      lines.push_back(reproduced_line(b, d.replay->b, d.replay->ticks));
    }
  }
  lines.push_back(verdict(d, a, b));
  return lines;
}

}  // namespace fixstep
