// The recording file format: line-oriented text, written by format_recording and read by
// parse_recording / read_recording. One line each:
//   fixstep-recording 5
//   scene PATH
//   [scene_text BYTES CHECKSUM, then the scene's lines, each as |LINE: recording_scene_text.cpp]
//   definition HASH            integrator NAME          precision f32|f64
//   dt SECONDS                 substeps N               [damping_split per_stage|per_step]
//   hash_every K
//   [rules NAME VERSION]       (version 4: the game rules the ticks were stepped with)
//   tick N push=AX,AY held=HEX pressed=HEX released=HEX pointer=X,Y drag=SLOT:GEN|none
//        [KIND=SLOT:GEN,X,Y]...   KIND: force, impulse, velocity, torque, angular_impulse,
//                                 angular_velocity or target_angle (body_input_kind_name)
//        [joint.KIND=SLOT:GEN,X,Y]...   a joint's input (joint_input_kind_name), after them
//        [axis.I=V]...   a game's axis I reading V (TickInput::axes; 0 is not written), last
// (one line; a body is named by its handle Entity{SLOT, GEN}, per-body inputs in order; the
// angular kinds carry their value in X, Y as recorded, 0 for input World::step applies).
// Joint inputs came with joints and changed no version, as the angular kinds did; so did the
// axes and the actions: a recording with rules may set any of the 32 action bits (the game's
// actions), one without rules only fixstep's default buttons (all_buttons).
// The angular kinds came with bodies with shapes and changed no version: only a world with
// shapes takes them, and a build before shapes refuses such a recording anyway (its scene's
// definition hash differs, and the tick line's `torque=` is not a kind it knows: "expected
// force=, impulse= or velocity=").
// Version 5 changed no line: from it the world's random generator is seeded through SplitMix64
// (Seeding::splitmix); a recording of version 4 or older replays with the seeding it was made
// with (Seeding::pcg32_srandom). Only a world with a seed other than 0 is written as version 5:
// with seed 0 both seedings give the same generator, and its recording stays 4 (3) for older
// builds (recording_version_of).
// Version 3 had no rules line (a recording without rules is still written as version 3).
// Version 2 had no scene_text and damping_split lines (the scene was read from PATH, with its
// own damping split); version 1 had no per-body
// inputs and named the dragged body by its dense INDEX, read as
// fixstep::defined_entity(INDEX) (exact for the worlds version 1 recorded, which destroyed
// nothing).
//   hash N HASH                (state hash after N ticks)
//   end TICKS HASH             (the last line; its absence means the file is truncated)
// A tick line is written only when the input differs from the previous tick's; numbers are
// the shortest text that reads back as the same double (fmt {} / a correctly rounded read).
// Lines end in \n; the reader also takes \r\n (a recording checked out on Windows with
// CRLF conversion) and drops the \r, so the same recording reads the same either way. A field
// or path quoted in a message has its control characters escaped (printable.hpp).
#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <locale>
#include <sstream>
#include <system_error>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/printable.hpp"
#include "fixstep/io/recording_file.hpp"
#include "recording_text.hpp"

namespace fixstep {

namespace {

using Kind = RecordingError::Kind;

/// Lines of `text` with their 1-based numbers; a last line without its newline is reported.
class Lines {
 public:
  Lines(std::string_view text, const std::string& file) : text_(text), file_(file) {}
  /// The next line without its \n (or \r\n), or nullopt at the end of the text. Throws
  /// truncated for a last line without its newline.
  std::optional<std::string_view> next() {
    if (pos_ >= text_.size()) return std::nullopt;
    const std::size_t end = text_.find('\n', pos_);
    ++line_;
    if (end == std::string_view::npos) {
      fail(Kind::truncated, "", "the last line ends without a newline (the file was cut short)");
    }
    std::string_view line = text_.substr(pos_, end - pos_);
    if (line.ends_with('\r')) line.remove_suffix(1);
    pos_ = end + 1;
    return line;
  }
  /// The start of the next line (up to its newline or the end of the text) without taking it:
  /// "" at the end. For optional lines, recognised by their first word.
  [[nodiscard]] std::string_view peek() const {
    if (pos_ >= text_.size()) return {};
    const std::size_t end = text_.find('\n', pos_);
    return text_.substr(pos_, end == std::string_view::npos ? std::string_view::npos : end - pos_);
  }
  [[noreturn]] void fail(Kind kind, std::string_view field, std::string_view message) const {
    throw RecordingError(kind, file_, line_, field, message);
  }
  [[nodiscard]] std::size_t line() const { return line_; }

 private:
  std::string_view text_;
  const std::string& file_;
  std::size_t pos_ = 0, line_ = 0;
};

/// Splits at single spaces.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (true) {
    const std::size_t j = line.find(' ', i);
    out.push_back(line.substr(i, j == std::string_view::npos ? std::string_view::npos : j - i));
    if (j == std::string_view::npos) return out;
    i = j + 1;
  }
}

std::string shown(std::string_view s) {
  return s.size() > 40 ? fmt::format("\"{}...\"", printable(s.substr(0, 40)))
                       : fmt::format("\"{}\"", printable(s));
}

template <class T>
T integer(const Lines& in, std::string_view text, std::string_view field, int base, T max) {
  T v{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v, base);
  if (ec != std::errc{} || end != text.data() + text.size() || text.empty() || v > max) {
    in.fail(Kind::corrupt, field,
            fmt::format("expected {} <= {}, found {}",
                        base == 16 ? "a hexadecimal integer" : "an integer", max, shown(text)));
  }
  return v;
}

std::uint64_t hash16(const Lines& in, std::string_view text, std::string_view field) {
  if (text.size() != 16) {
    in.fail(Kind::corrupt, field, fmt::format("expected 16 hex digits, found {}", shown(text)));
  }
  return integer<std::uint64_t>(in, text, field, 16, std::numeric_limits<std::uint64_t>::max());
}

/// A number as std::from_chars reads it (an optional '-', digits, '.', an exponent: no space,
/// '+', hexadecimal, inf or nan), correctly rounded, in the classic locale whatever the
/// program's. Not from_chars itself: libc++ 13 (emscripten 3.1.6) has none for double.
double real(const Lines& in, std::string_view text, std::string_view field) {
  const bool plain = !text.empty() && text[0] != '+' &&
                     text.find_first_not_of("0123456789.eE+-") == std::string_view::npos;
  thread_local std::istringstream number = [] {
    std::istringstream s;
    s.imbue(std::locale::classic());
    return s;
  }();
  number.clear();
  number.str(std::string(text));
  double v = 0.0;
  number >> std::noskipws >> v;
  if (!plain || number.fail() || number.peek() != std::char_traits<char>::eof()) {
    in.fail(Kind::corrupt, field, fmt::format("expected a number, found {}", shown(text)));
  }
  if (!std::isfinite(v)) in.fail(Kind::corrupt, field, fmt::format("must be finite (got {})", v));
  return v;
}

Vec2 vec2(const Lines& in, std::string_view text, std::string_view field) {
  const std::size_t comma = text.find(',');
  if (comma == std::string_view::npos) {
    in.fail(Kind::corrupt, field, fmt::format("expected X,Y, found {}", shown(text)));
  }
  return {real(in, text.substr(0, comma), field), real(in, text.substr(comma + 1), field)};
}

/// Action bits: any of the 32 in a recording with rules (the game's actions), else fixstep's
/// default ones only (all_buttons).
std::uint32_t buttons(const Lines& in, std::string_view text, std::string_view field,
                      const Recording& rec) {
  const auto v = integer<std::uint32_t>(in, text, field, 16, 0xffffffffu);
  if (rec.rules_name.empty() && (v & ~all_buttons) != 0) {
    in.fail(Kind::corrupt, field,
            fmt::format("bits {:x} are not buttons (hexadecimal; the buttons of a recording "
                        "without rules are the bits of {:x})",
                        v & ~all_buttons, all_buttons));
  }
  return v;
}

/// `KEY=VALUE` with the expected key; returns VALUE.
std::string_view keyed(const Lines& in, std::string_view word, std::string_view key) {
  if (word.size() <= key.size() || word.substr(0, key.size()) != key || word[key.size()] != '=') {
    in.fail(Kind::corrupt, key, fmt::format("expected {}=..., found {}", key, shown(word)));
  }
  return word.substr(key.size() + 1);
}

/// The words of a line "KEY ...", checked for the key and the word count.
std::vector<std::string_view> fields(const Lines& in, std::string_view line, std::string_view key,
                                     std::size_t count) {
  std::vector<std::string_view> w = words(line);
  if (w[0] != key) {
    in.fail(Kind::corrupt, key, fmt::format("expected the `{}` line, found {}", key, shown(line)));
  }
  if (w.size() != count) {
    in.fail(Kind::corrupt, key,
            fmt::format("expected {} words separated by single spaces, found {}", count, w.size()));
  }
  return w;
}

std::string_view header_line(Lines& in, std::string_view key) {
  const auto line = in.next();
  if (!line) in.fail(Kind::truncated, key, "the file ends inside the header");
  return fields(in, *line, key, 2)[1];
}

void read_version(Lines& in, Recording& rec) {
  const auto line = in.next();
  if (!line) {
    in.fail(Kind::truncated, "",
            "empty file, not a recording (`fixstep run SCENE --steps N --record FILE` writes one)");
  }
  const std::vector<std::string_view> w = words(*line);
  if (w[0] != recording_magic) {
    // A scene given instead is the likely slip: TOML starts with a table, a key or a comment.
    const bool toml = line->starts_with('[') || line->starts_with('#') ||
                      line->find('=') != std::string_view::npos;
    in.fail(Kind::foreign, "",
            fmt::format("not a fixstep recording: the first line is {}, a recording's is `{} {}`{}",
                        shown(*line), recording_magic, recording_version_without_rules,
                        toml ? " (this looks like a TOML scene: replay takes a recording made by "
                               "`fixstep run SCENE --steps N --record FILE`)"
                             : ""));
  }
  if (w.size() != 2) in.fail(Kind::corrupt, "version", "expected `fixstep-recording VERSION`");
  const int version = integer<int>(in, w[1], "version", 10, std::numeric_limits<int>::max());
  if (version < 1) in.fail(Kind::corrupt, "version", "must be >= 1");
  if (version > recording_version) {
    in.fail(Kind::unsupported_version, "version",
            fmt::format("recording format version {}; this build reads version {} and older: "
                        "replay it with the newer fixstep that wrote it",
                        version, recording_version));
  }
  rec.version = version;
  // Before version 5 the world's generator was seeded without SplitMix64 (random.hpp).
  rec.settings.seeding = version >= recording_version ? Seeding::splitmix : Seeding::pcg32_srandom;
}

/// The embedded scene's section (recording_scene_text.cpp), from its `scene_text BYTES CHECKSUM`
/// line on: every error names the line it is on.
void read_scene_text(Lines& in, std::string_view first, Recording& rec) {
  const std::vector<std::string_view> w = fields(in, first, "scene_text", 3);
  const auto bytes =
      integer<std::uint64_t>(in, w[1], "scene_text", 10, std::numeric_limits<std::uint64_t>::max());
  if (bytes == 0 || bytes > max_recording_scene_bytes) {
    in.fail(Kind::corrupt, "scene_text",
            bytes == 0 ? std::string("an embedded scene of 0 bytes (a recording without a scene "
                                     "has no scene_text section)")
                       : fmt::format("an embedded scene of {} bytes; a scene may have at most {} "
                                     "bytes (the scene size limit)",
                                     bytes, max_recording_scene_bytes));
  }
  recording_text::SceneTextDecoder scene(static_cast<std::size_t>(bytes),
                                         hash16(in, w[2], "scene_text"));
  while (!scene.done()) {
    const auto line = in.next();
    if (!line) {
      in.fail(Kind::truncated, "scene_text",
              fmt::format("the file ends inside the embedded scene ({} of its {} bytes read): the "
                          "recording was cut short",
                          scene.size(), bytes));
    }
    if (const std::string e = scene.take(*line); !e.empty())
      in.fail(Kind::corrupt, "scene_text", e);
  }
  if (const std::string e = scene.finish(rec.scene_text); !e.empty()) {
    in.fail(Kind::corrupt, "scene_text", e);
  }
}

/// `rules NAME VERSION` (version 4): the rules the recording needs.
void read_rules(Lines& in, Recording& rec) {
  const std::vector<std::string_view> w = words(*in.next());  // peeked: the line is there
  if (w.size() != 3) in.fail(Kind::corrupt, "rules", "expected `rules NAME VERSION`");
  if (const std::string fault = rules_name_fault(w[1]); !fault.empty()) {
    in.fail(Kind::corrupt, "rules", "the name " + fault);
  }
  rec.rules_name = std::string(w[1]);
  rec.rules_version =
      integer<std::uint32_t>(in, w[2], "rules", 10, std::numeric_limits<std::uint32_t>::max());
  if (rec.rules_version < 1) in.fail(Kind::corrupt, "rules", "the version must be >= 1");
}

/// The `scene PATH` line and, from version 3, the optional scene_text section after it.
void read_scene(Lines& in, Recording& rec) {
  {
    const auto line = in.next();
    if (!line) in.fail(Kind::truncated, "scene", "the file ends inside the header");
    if (line->substr(0, 6) != "scene " || line->size() == 6) {
      in.fail(Kind::corrupt, "scene", "expected `scene PATH`");
    }
    rec.scene = std::string(line->substr(6));
    for (const char c : rec.scene) {  // a NUL in the path: found by fuzz_recording
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
        in.fail(Kind::corrupt, "scene",
                fmt::format("the path {} holds a control character", shown(rec.scene)));
      }
    }
  }
  if (rec.version >= 3 && in.peek().starts_with("scene_text ")) {
    read_scene_text(in, *in.next(), rec);
  }
}

void read_header(Lines& in, Recording& rec) {
  read_version(in, rec);
  read_scene(in, rec);
  rec.definition_hash = hash16(in, header_line(in, "definition"), "definition");
  const std::string_view integrator = header_line(in, "integrator");
  const auto i = parse_integrator(integrator);
  if (!i) in.fail(Kind::corrupt, "integrator", fmt::format("unknown {}", shown(integrator)));
  rec.settings.integrator = *i;
  const std::string_view precision = header_line(in, "precision");
  const auto p = parse_precision(precision);
  if (!p) in.fail(Kind::corrupt, "precision", fmt::format("unknown {}", shown(precision)));
  rec.settings.precision = *p;
  rec.settings.dt = real(in, header_line(in, "dt"), "dt");
  if (!(rec.settings.dt > 0.0 && rec.settings.dt <= 1.0)) {
    in.fail(Kind::corrupt, "dt", fmt::format("must be > 0 and <= 1 s (got {})", rec.settings.dt));
  }
  rec.settings.substeps = integer<int>(in, header_line(in, "substeps"), "substeps", 10, 1000000);
  if (rec.settings.substeps < 1) in.fail(Kind::corrupt, "substeps", "must be >= 1");
  if (rec.version >= 3 && in.peek().starts_with("damping_split ")) {
    const std::string_view split = header_line(in, "damping_split");
    rec.settings.damping_split = parse_damping_split(split);
    if (!rec.settings.damping_split) {
      in.fail(Kind::corrupt, "damping_split",
              fmt::format("unknown {} (per_stage or per_step)", shown(split)));
    }
  }
  rec.hash_every = integer<std::uint64_t>(in, header_line(in, "hash_every"), "hash_every", 10,
                                          max_recording_ticks);
  if (rec.hash_every < 1) in.fail(Kind::corrupt, "hash_every", "must be >= 1");
  if (rec.hash_every > max_hash_every) {  // recording.hpp: the claimed ticks follow the file's size
    in.fail(Kind::corrupt, "hash_every",
            fmt::format("{} ticks between state hashes; a recording stores one at least every {} "
                        "ticks (record with --hash-every {} or less)",
                        rec.hash_every, max_hash_every, max_hash_every));
  }
  if (rec.version >= 4 && in.peek().starts_with("rules ")) read_rules(in, rec);
}

/// `SLOT:GEN` (version 2's handle; slot and generation >= 1).
Entity handle(const Lines& in, std::string_view text, std::string_view field) {
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos) {
    in.fail(Kind::corrupt, field, fmt::format("expected SLOT:GENERATION, found {}", shown(text)));
  }
  const Entity e{integer<std::uint32_t>(in, text.substr(0, colon), field, 10, 0xffffffffu),
                 integer<std::uint32_t>(in, text.substr(colon + 1), field, 10, 0xffffffffu)};
  if (e.index1 == 0 || e.generation == 0) {
    in.fail(Kind::corrupt, field, fmt::format("slot and generation must be >= 1 ({})", text));
  }
  return e;
}

/// `KIND=SLOT:GEN,X,Y`: one per-body input of version 2.
BodyInput body_input(const Lines& in, std::string_view word) {
  const std::size_t eq = word.find('=');
  const std::string_view key = word.substr(0, eq);
  BodyInput b;
  bool known = false;
  for (int k = 0; k <= static_cast<int>(last_body_input_kind) && !known; ++k) {
    b.kind = static_cast<BodyInputKind>(k);
    known = key == body_input_kind_name(b.kind);
  }
  if (!known) {
    in.fail(Kind::corrupt, "tick",
            fmt::format("expected force=, impulse=, velocity=, torque=, angular_impulse=, "
                        "angular_velocity= or target_angle=, found {}",
                        shown(word)));
  }
  const std::string_view value = keyed(in, word, key);
  const std::size_t comma = value.find(',');
  if (comma == std::string_view::npos) {
    in.fail(Kind::corrupt, key, fmt::format("expected SLOT:GEN,X,Y, found {}", shown(value)));
  }
  b.body = handle(in, value.substr(0, comma), key);
  b.value = vec2(in, value.substr(comma + 1), key);
  return b;
}

/// `joint.KIND=SLOT:GEN,X,Y`: one joint input.
JointInput joint_input(const Lines& in, std::string_view word) {
  const std::size_t eq = word.find('=');
  const std::string_view key = word.substr(0, eq);
  JointInput j;
  bool known = false;
  for (int k = 0; k <= static_cast<int>(last_joint_input_kind) && !known; ++k) {
    j.kind = static_cast<JointInputKind>(k);
    known = key.substr(6) == joint_input_kind_name(j.kind);
  }
  if (!known) {
    in.fail(Kind::corrupt, "tick",
            fmt::format("expected joint.motor_speed=, joint.max_motor_torque=, "
                        "joint.max_motor_force=, joint.enable_motor=, joint.target= or "
                        "joint.target_angle=, found {}",
                        shown(word)));
  }
  const std::string_view value = keyed(in, word, key);
  const std::size_t comma = value.find(',');
  if (comma == std::string_view::npos) {
    in.fail(Kind::corrupt, key, fmt::format("expected SLOT:GEN,X,Y, found {}", shown(value)));
  }
  j.joint = [&] {
    const Entity e = handle(in, value.substr(0, comma), key);
    return Joint{e.index1, e.generation};
  }();
  j.value = vec2(in, value.substr(comma + 1), key);
  return j;
}

/// `axis.I=V`: axis I (< max_axes, after the axes already read: `seen` of them, the last one's
/// index + 1) reads V, finite and in [-1, 1], not 0 (a 0 axis is not written).
void axis_word(const Lines& in, std::string_view word, TickInput& t, std::size_t& seen) {
  const std::size_t eq = word.find('=');
  if (eq == std::string_view::npos) {
    in.fail(Kind::corrupt, "axis", fmt::format("expected axis.I=V, found {}", shown(word)));
  }
  const auto index = integer<std::size_t>(in, word.substr(5, eq - 5), "axis", 10, max_axes - 1);
  if (index < seen) {
    in.fail(Kind::corrupt, "axis",
            fmt::format("{}: the axes come in increasing index, each once", shown(word)));
  }
  const double v = real(in, word.substr(eq + 1), "axis");
  if (!(v >= -1.0 && v <= 1.0) || v == 0.0) {
    in.fail(Kind::corrupt, "axis",
            fmt::format("{}: an axis reads a value in [-1, 1], and 0 is not written", shown(word)));
  }
  t.axes[index] = v;
  seen = index + 1;
}

TickInput tick_line(const Lines& in, std::string_view line, const Recording& rec) {
  // Version 2 appends the per-body inputs to version 1's eight words.
  const std::size_t count = words(line).size();
  const bool v2 = rec.version >= 2;
  if (v2 && count > 8 + max_body_inputs + max_joint_inputs + max_axes) {
    in.fail(Kind::corrupt, "tick",
            fmt::format("{} per-body and joint inputs; at most {} per tick", count - 8,
                        max_body_inputs + max_joint_inputs));
  }
  const std::vector<std::string_view> w = fields(in, line, "tick", v2 && count > 8 ? count : 8);
  TickInput t;
  t.tick = integer<std::uint64_t>(in, w[1], "tick", 10, max_recording_ticks - 1);
  if (rec.inputs.empty() ? t.tick != 0 : t.tick <= rec.inputs.back().tick) {
    in.fail(Kind::corrupt, "tick",
            rec.inputs.empty()
                ? fmt::format("the first tick line must be tick 0 (got {})", t.tick)
                : fmt::format("ticks out of order: {} after {}", t.tick, rec.inputs.back().tick));
  }
  t.push = vec2(in, keyed(in, w[2], "push"), "push");
  t.held = buttons(in, keyed(in, w[3], "held"), "held", rec);
  t.pressed = buttons(in, keyed(in, w[4], "pressed"), "pressed", rec);
  t.released = buttons(in, keyed(in, w[5], "released"), "released", rec);
  t.pointer = vec2(in, keyed(in, w[6], "pointer"), "pointer");
  const std::string_view drag = keyed(in, w[7], "drag");
  if (drag == "none") {
    t.drag_body = null_entity;
  } else if (rec.version >= 2) {
    t.drag_body = handle(in, drag, "drag");
  } else {
    t.drag_body =
        fixstep::defined_entity(integer<std::uint32_t>(in, drag, "drag", 10, 0xfffffffeu));
  }
  std::size_t axes_seen = 0;  // axis words come last, in increasing index
  for (std::size_t k = 8; k < w.size(); ++k) {
    if (w[k].starts_with("axis.")) {
      axis_word(in, w[k], t, axes_seen);
    } else if (axes_seen != 0) {
      in.fail(Kind::corrupt, "tick",
              fmt::format("{} after an axis: the axes come last", shown(w[k])));
    } else if (w[k].starts_with("joint.")) {
      t.joints.push_back(joint_input(in, w[k]));
    } else if (!t.joints.empty()) {
      in.fail(Kind::corrupt, "tick",
              fmt::format("{} after a joint input: per-body inputs come first", shown(w[k])));
    } else {
      t.bodies.push_back(body_input(in, w[k]));
    }
  }
  if (t.bodies.size() > max_body_inputs || t.joints.size() > max_joint_inputs) {
    in.fail(Kind::corrupt, "tick",
            fmt::format("{} per-body inputs and {} joint inputs; at most {} and {} per tick",
                        t.bodies.size(), t.joints.size(), max_body_inputs, max_joint_inputs));
  }
  return t;
}

void hash_line(const Lines& in, std::string_view line, Recording& rec) {
  const std::vector<std::string_view> w = fields(in, line, "hash", 3);
  const auto tick = integer<std::uint64_t>(in, w[1], "hash", 10, max_recording_ticks);
  if (tick == 0 || (!rec.hashes.empty() && tick <= rec.hashes.back().first)) {
    in.fail(Kind::corrupt, "hash",
            tick == 0
                ? std::string("tick must be >= 1")
                : fmt::format("ticks out of order: {} after {}", tick, rec.hashes.back().first));
  }
  rec.hashes.emplace_back(tick, hash16(in, w[2], "hash"));
}

void end_line(const Lines& in, std::string_view line, Recording& rec) {
  const std::vector<std::string_view> w = fields(in, line, "end", 3);
  rec.ticks = integer<std::uint64_t>(in, w[1], "end", 10, max_recording_ticks);
  rec.final_hash = hash16(in, w[2], "end");
  if (!rec.inputs.empty() && rec.inputs.back().tick >= rec.ticks) {
    in.fail(Kind::corrupt, "end",
            fmt::format("a tick line for tick {} is beyond the end ({} ticks)",
                        rec.inputs.back().tick, rec.ticks));
  }
  if (rec.ticks > 0 && rec.inputs.empty()) {
    in.fail(Kind::corrupt, "end", fmt::format("{} ticks but no tick lines", rec.ticks));
  }
  if (!rec.hashes.empty() && rec.hashes.back().first > rec.ticks) {
    in.fail(Kind::corrupt, "end",
            fmt::format("a hash for tick {} is beyond the end ({} ticks)", rec.hashes.back().first,
                        rec.ticks));
  }
  // A recorder stores a hash every hash_every ticks, so no stretch of the replay goes longer
  // unchecked and the ticks claimed are bounded by the file's lines (max_hash_every): refused here,
  // before a tick is replayed.
  std::uint64_t last = 0;
  for (std::size_t i = 0; i <= rec.hashes.size(); ++i) {
    const std::uint64_t next = i < rec.hashes.size() ? rec.hashes[i].first : rec.ticks;
    if (next - last > rec.hash_every) {
      in.fail(Kind::corrupt, "end",
              fmt::format("{} ticks claimed, but no state hash between ticks {} and {}: a "
                          "recording stores one every hash_every = {} ticks",
                          rec.ticks, last, next, rec.hash_every));
    }
    last = next;
  }
}

}  // namespace

Recording parse_recording(std::string_view text, const std::string& source_name) {
  const IeeeFloatMode ieee;  // dt and inputs read by strtod, which rounds in the current mode
  if (text.size() > max_recording_bytes) {
    throw RecordingError(Kind::corrupt, source_name, 0, "",
                         fmt::format("{} bytes; recordings are limited to {} bytes", text.size(),
                                     max_recording_bytes));
  }
  Lines in(text, source_name);
  Recording rec;
  read_header(in, rec);
  while (const auto line = in.next()) {
    if (line->starts_with("tick ")) {
      rec.inputs.push_back(tick_line(in, *line, rec));
    } else if (line->starts_with("hash ")) {
      hash_line(in, *line, rec);
    } else if (line->starts_with("end ")) {
      end_line(in, *line, rec);
      if (const auto extra = in.next()) {
        in.fail(Kind::corrupt, "",
                fmt::format("text after the `end` line, which must be the last: found {}",
                            shown(*extra)));
      }
      return rec;
    } else {
      in.fail(Kind::corrupt, "",
              fmt::format("expected a `tick`, `hash` or `end` line, found {}", shown(*line)));
    }
  }
  in.fail(Kind::truncated, "end",
          "no `end` line: the recording was cut short (the session did not finish writing it)");
}

}  // namespace fixstep
