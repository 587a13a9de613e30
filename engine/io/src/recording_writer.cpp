// The streaming recorder (recording_writer.hpp): the lines format_recording writes, in the same
// order, appended as the ticks come.
#include "fixstep/io/recording_writer.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_def.hpp"
#include "recording_text.hpp"

namespace fixstep {

namespace {
constexpr std::size_t flush_at = 1 << 16;  // bytes buffered before they go to the file
}  // namespace

RecordingWriter::RecordingWriter(const WorldDef& def, std::string scene, std::uint64_t hash_every,
                                 std::filesystem::path file, std::string_view scene_text)
    : out_(std::move(file)), hash_every_(hash_every) {
  if (hash_every == 0 || hash_every > max_hash_every) {
    throw std::invalid_argument(fmt::format("RecordingWriter: hash_every must be 1 .. {} (got {})",
                                            max_hash_every, hash_every));
  }
  head_.scene = std::move(scene);  // the header's fields only
  head_.scene_text = scene_text;
  head_.definition_hash = definition_hash(def);
  head_.settings = recorded_settings(def);
  head_.hash_every = hash_every;
  line_ = recording_text::header(head_);
  kept_ = line_.size();
}

void RecordingWriter::set_rules(std::string name, std::uint32_t version) {
  if (ticks_ != 0) throw std::logic_error("RecordingWriter::set_rules: after the first tick");
  if (const std::string fault = rules_name_fault(name); !fault.empty()) {
    throw std::invalid_argument("RecordingWriter::set_rules: the rules name " + fault);
  }
  if (version == 0) {
    throw std::invalid_argument("RecordingWriter::set_rules: the version must be >= 1");
  }
  head_.rules_name = std::move(name);
  head_.rules_version = version;
  line_ = recording_text::header(head_);  // nothing is written before the first tick's flush
  kept_ = line_.size();
}

void RecordingWriter::flush_if_full() {
  if (out_.size() + line_.size() > max_recording_bytes) {
    throw RecordingError(
        RecordingError::Kind::corrupt, out_.file().string(), 0, "",
        fmt::format("the recording would exceed the {} bytes a recording may have, at tick {}: "
                    "record fewer ticks, a larger --hash-every or fewer input changes",
                    max_recording_bytes, ticks_));
  }
  // Only the lines up to the last hash line go to the file: the ones after it stay here (at most
  // hash_every ticks' input changes), so that finish_at_last_hash can drop them.
  if (line_.size() >= flush_at && kept_ > 0) {
    out_.append(std::string_view(line_).substr(0, kept_));
    line_.erase(0, kept_);
    kept_ = 0;
  }
}

void RecordingWriter::record(const TickInput& input, const World& after_the_tick) {
  if (ticks_ == 0) head_ = Recording{};  // the header is written: its scene text is not kept
  if (after_the_tick.tick() != ticks_ + 1) {
    throw std::invalid_argument(fmt::format(
        "RecordingWriter::record: the simulation is at tick {}, the recording expects tick {}",
        after_the_tick.tick(), ticks_ + 1));
  }
  TickInput in = input;
  in.tick = ticks_;
  // A tick line only when the input differs from the previous tick's (run-length, as Recorder).
  const bool same = have_last_ && [&] {
    TickInput last = last_;
    last.tick = in.tick;
    return last == in;
  }();
  if (!same) {
    recording_text::append_tick(line_, in);
    last_ = in, have_last_ = true;
  }
  ticks_ += 1;
  if (ticks_ % hash_every_ == 0) {
    last_hash_ = after_the_tick.state_hash();
    last_hash_tick_ = ticks_;
    recording_text::append_hash(line_, ticks_, last_hash_);
    kept_ = line_.size();
  }
  flush_if_full();
}

void RecordingWriter::finish(const World& sim) {
  if (sim.tick() != ticks_) {
    throw std::invalid_argument(
        fmt::format("RecordingWriter::finish: the simulation is at tick {}, the recording has {} "
                    "ticks",
                    sim.tick(), ticks_));
  }
  recording_text::append_end(line_, ticks_, sim.state_hash());
  out_.append(line_);
  line_.clear();
  out_.commit();
}

void RecordingWriter::finish_at_last_hash(std::uint64_t initial_hash) {
  line_.resize(kept_);  // the tick lines after the last hash line
  recording_text::append_end(line_, last_hash_tick_,
                             last_hash_tick_ == 0 ? initial_hash : last_hash_);
  out_.append(line_);
  line_.clear();
  out_.commit();
}

}  // namespace fixstep
