// The writing half of the recording format (recording_text.hpp, format_recording): the lines
// format_recording and the streaming RecordingWriter both write. The format itself and its
// reader are in recording_format.cpp.
#include "recording_text.hpp"

#include <fmt/format.h>

#include <iterator>
#include <limits>
#include <stdexcept>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/printable.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"

namespace fixstep {

namespace recording_text {

void append_tick(std::string& out, const TickInput& t) {
  fmt::format_to(
      std::back_inserter(out),
      "tick {} push={},{} held={:x} pressed={:x} released={:x} pointer={},{} drag=", t.tick,
      t.push.x, t.push.y, t.held, t.pressed, t.released, t.pointer.x, t.pointer.y);
  if (t.drag_body == null_entity) {
    out += "none";
  } else {
    fmt::format_to(std::back_inserter(out), "{}:{}", t.drag_body.index1, t.drag_body.generation);
  }
  for (const BodyInput& b : t.bodies) {
    fmt::format_to(std::back_inserter(out), " {}={}:{},{},{}", body_input_kind_name(b.kind),
                   b.body.index1, b.body.generation, b.value.x, b.value.y);
  }
  for (const JointInput& j : t.joints) {
    fmt::format_to(std::back_inserter(out), " joint.{}={}:{},{},{}", joint_input_kind_name(j.kind),
                   j.joint.index1, j.joint.generation, j.value.x, j.value.y);
  }
  for (std::size_t i = 0; i < max_axes; ++i) {
    if (t.axes[i] != 0.0) fmt::format_to(std::back_inserter(out), " axis.{}={}", i, t.axes[i]);
  }
  out += '\n';
}

std::string header(const Recording& rec) {
  for (const char c : rec.scene) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      throw std::invalid_argument(
          fmt::format("cannot record the scene \"{}\": its path holds a control character, "
                      "and a recording stores the path on one line; rename the file",
                      printable(rec.scene)));
    }
  }
  // Version 5 for the mixed seeding; 4 or 3 for a recording replayed with the older seeding.
  const int version = recording_version_of(rec);
  std::string out = fmt::format("{} {}\nscene {}\n", recording_magic, version, rec.scene);
  // Optional sections follow the scene line, each announced by its own keyword.
  if (!rec.scene_text.empty()) append_scene_text(out, rec.scene_text);
  fmt::format_to(std::back_inserter(out),
                 "definition {}\nintegrator {}\nprecision {}\ndt {}\nsubsteps {}\n",
                 hex_hash(rec.definition_hash), integrator_name(rec.settings.integrator),
                 precision_name(rec.settings.precision), rec.settings.dt, rec.settings.substeps);
  if (const auto split = rec.settings.damping_split) {
    fmt::format_to(std::back_inserter(out), "damping_split {}\n", damping_split_name(*split));
  }
  fmt::format_to(std::back_inserter(out), "hash_every {}\n", rec.hash_every);
  if (!rec.rules_name.empty()) {
    fmt::format_to(std::back_inserter(out), "rules {} {}\n", rec.rules_name, rec.rules_version);
  }
  return out;
}

void append_hash(std::string& out, std::uint64_t tick, std::uint64_t hash) {
  fmt::format_to(std::back_inserter(out), "hash {} {}\n", tick, hex_hash(hash));
}

void append_end(std::string& out, std::uint64_t ticks, std::uint64_t hash) {
  fmt::format_to(std::back_inserter(out), "end {} {}\n", ticks, hex_hash(hash));
}

}  // namespace recording_text

std::string format_recording(const Recording& rec) {
  std::string out = recording_text::header(rec);
  std::size_t h = 0;
  auto hashes_until = [&](std::uint64_t tick) {
    for (; h < rec.hashes.size() && rec.hashes[h].first <= tick; ++h) {
      recording_text::append_hash(out, rec.hashes[h].first, rec.hashes[h].second);
    }
  };
  for (const TickInput& t : rec.inputs) {
    hashes_until(t.tick);
    recording_text::append_tick(out, t);
  }
  hashes_until(std::numeric_limits<std::uint64_t>::max());
  recording_text::append_end(out, rec.ticks, rec.final_hash);
  return out;
}

}  // namespace fixstep
