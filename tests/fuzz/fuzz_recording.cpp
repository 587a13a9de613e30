// libFuzzer target: arbitrary bytes as a recording file. A clean rejection is a
// RecordingError; a recording that reads must write back to the same recording (format →
// parse is exact), a body it names that the small world lacks is a clean rejection
// (check_recorded_bodies), and a short one must replay on a small world without any other
// exception.
// Any other exception, a crash or a sanitizer report is a finding. Built by the `fuzz` preset
// (clang only); run as in docs/ROBUSTNESS.md, "Fuzzing".
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fixstep/core/components.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <string>
#include <string_view>

#include "fixstep/io/recording_file.hpp"
#include "link_between.hpp"

namespace {

/// Two bodies, one link: enough for replay to step every recorded input (push, drag index).
const fixstep::WorldDef& small_world() {
  static const fixstep::WorldDef def = [] {
    fixstep::WorldDef d;
    d.settings.dt = 0.01;
    fixstep::BodyDef a, b;
    a.body = {1.0, {0.0, 0.0}, {0.0, 0.0}};
    a.spring = fixstep::SpringDamper{{0.0, 0.0}, 10.0, 0.1, 0.0};
    b.body = {1.0, {1.0, 0.0}, {0.0, 0.0}};
    d.bodies = {a, b};
    d.links = {fixstep::test::link_between(0, 1, fixstep::LinkSpring{10.0, 0.1, 1.0})};
    return d;
  }();
  return def;
}

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_recording: FINDING: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fixstep::Recording rec;
  try {
    rec = fixstep::parse_recording(text, "fuzz.rec");
  } catch (const fixstep::RecordingError&) {
    return 0;  // a clean rejection
  } catch (const std::exception& e) {
    finding(std::string("parse_recording threw a non-RecordingError: ") + e.what());
  }
  try {
    // format_recording writes the current version: an older recording comes back as the
    // current version with the same content (an embedded scene's bytes included).
    fixstep::Recording again = fixstep::parse_recording(fixstep::format_recording(rec), "again");
    again.version = rec.version;
    if (again != rec) {
      finding("format_recording then parse_recording does not give the same recording");
    }
    // A body the small world does not have is a clean rejection, as in `fixstep replay`.
    fixstep::check_recorded_bodies(rec, small_world().bodies.size(), small_world().joints.size(),
                                   "fuzz.rec");
    if (rec.ticks <= 2000) {
      fixstep::World sim = fixstep::World(small_world());
      (void)fixstep::replay(sim, rec);  // a mismatch is expected; an exception is not
    }
  } catch (const fixstep::RecordingError& e) {
    if (e.kind() != fixstep::RecordingError::Kind::corrupt) {
      finding(std::string("check_recorded_bodies threw a RecordingError not corrupt: ") + e.what());
    }
  } catch (const std::exception& e) {
    finding(std::string("a recording that reads failed afterwards: ") + e.what());
  }
  return 0;
}
