// A recording that cannot be used (recording_file.hpp): RecordingError's message, the check of
// the bodies a recording names, and the replay that first checks the world is the recorded one.
#include <fmt/format.h>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/io/printable.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"

namespace fixstep {

std::string_view recording_error_name(RecordingError::Kind kind) {
  switch (kind) {
    case RecordingError::Kind::unreadable:
      return "unreadable";
    case RecordingError::Kind::foreign:
      return "foreign";
    case RecordingError::Kind::unsupported_version:
      return "unsupported_version";
    case RecordingError::Kind::truncated:
      return "truncated";
    case RecordingError::Kind::corrupt:
      return "corrupt";
    case RecordingError::Kind::scene_mismatch:
      return "scene_mismatch";
    case RecordingError::Kind::needs_rules:
      return "needs_rules";
  }
  return "unknown";
}

namespace {
std::string error_text(const std::string& file, std::size_t line, std::string_view field,
                       std::string_view message) {
  std::string where = printable(file);
  if (line > 0) where += fmt::format(":{}", line);
  if (!field.empty()) where += fmt::format(": {}", field);
  return fmt::format("{}: {}", where, message);
}
}  // namespace

RecordingError::RecordingError(Kind kind, const std::string& file, std::size_t line,
                               std::string_view field, std::string_view message)
    : std::runtime_error(error_text(file, line, field, message)), kind_(kind), line_(line) {}

void check_physics_only(const Recording& rec, const std::string& file) {
  if (rec.rules_name.empty()) return;
  throw RecordingError(
      RecordingError::Kind::needs_rules, file, 0, "rules",
      fmt::format("recorded by {} with its game rules (version {}); physics alone would step "
                  "another game: replay it with that program's --replay {}",
                  rec.rules_name, rec.rules_version, printable(file)));
}

ReplayReport replay(const WorldDef& def, const Recording& rec, const TickRules& rules) {
  const std::uint64_t actual = definition_hash(def);
  if (actual != rec.definition_hash) {
    throw RecordingError(
        RecordingError::Kind::scene_mismatch, rec.scene, 0, "definition",
        fmt::format("the scene no longer matches the recording: its bodies, springs, planes or "
                    "settings changed (definition hash {}, recorded {}); replay it with the world "
                    "as it was recorded",
                    hex_hash(actual), hex_hash(rec.definition_hash)));
  }
  WorldDef recorded = def;
  recorded.allow_unstable = true;  // the recorded run ran: replay it whatever the guard says
  World sim = World(recorded);
  return replay(sim, rec, rules);
}

void check_recorded_bodies(const Recording& rec, std::size_t bodies, std::size_t joints,
                           const std::string& file) {
  auto check = [&](const TickInput& in, Entity e, std::string_view field) {
    if (e == null_entity || (e.index1 <= bodies && e == fixstep::defined_entity(e.index1 - 1)))
      return;
    throw RecordingError(
        RecordingError::Kind::corrupt, file, 0, field,
        fmt::format("the tick {} line names body {}:{}, which the scene does not have (its {} "
                    "bodies are 1:1 .. {}:1); the recording was edited or made with another "
                    "scene",
                    in.tick, e.index1, e.generation, bodies, bodies));
  };
  for (const TickInput& in : rec.inputs) {
    check(in, in.drag_body, "drag");
    for (const BodyInput& b : in.bodies) {
      check(in, b.body, body_input_kind_name(b.kind));
    }
    for (const JointInput& j : in.joints) {  // a scene's joints are 1:1 .. N:1, as its bodies
      if (j.joint.index1 >= 1 && j.joint.index1 <= joints && j.joint.generation == 1) continue;
      const std::string has = joints == 0
                                  ? std::string("it has no joints")
                                  : fmt::format("its {} joints are 1:1 .. {}:1", joints, joints);
      throw RecordingError(
          RecordingError::Kind::corrupt, file, 0, joint_input_kind_name(j.kind),
          fmt::format("the tick {} line names joint {}:{}, which the scene does not have ({}); "
                      "the recording was edited or made with another scene",
                      in.tick, j.joint.index1, j.joint.generation, has));
    }
  }
}

}  // namespace fixstep
