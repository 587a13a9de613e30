// A recording streamed to its file tick by tick: what `fixstep run --record`
// uses, so that a run of 10^8 ticks records in the same few kilobytes of memory as one of 10.
// The bytes are format_recording's for the same session; the file appears under its name only
// when finish() renames it into place (AtomicOutput).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/io/atomic_output.hpp"
#include "fixstep/io/recording_file.hpp"

namespace fixstep {

/// Records a live session into `file` as it runs: O(1) memory (the last tick's input and a line
/// buffer). Unlike Recorder it cannot truncate (rewind), so programs that rewind keep Recorder.
class RecordingWriter {
 public:
  /// Starts the recording of the world `def` (its definition hash and settings), named `scene`
  /// in the file and carrying `scene_text` (the bytes of the scene `def` was loaded from, or
  /// empty: Recording::scene_text; more than max_recording_scene_bytes is
  /// std::invalid_argument), storing the state hash every `hash_every` ticks
  /// (1 .. max_hash_every, else std::invalid_argument), and creates the temporary file beside
  /// `file` (std::runtime_error naming the file and the system's reason when it cannot, e.g. a
  /// missing directory).
  RecordingWriter(const WorldDef& def, std::string scene, std::uint64_t hash_every,
                  std::filesystem::path file, std::string_view scene_text = {});

  /// Names the rules the recording needs, as Recorder::set_rules (std::invalid_argument for a
  /// name rules_name_fault refuses or version 0). Before the first tick only (std::logic_error
  /// after it).
  void set_rules(std::string name, std::uint32_t version);

  /// Appends one tick, as Recorder::record (std::invalid_argument when after_the_tick.tick()
  /// is not ticks() + 1). Throws RecordingError corrupt when the file would grow beyond
  /// max_recording_bytes (a recording the reader refuses), std::runtime_error on a write error;
  /// the temporary file is then removed.
  void record(const TickInput& input, const World& after_the_tick);
  /// Ends the recording at `sim`'s state (its tick() must be ticks(), else
  /// std::invalid_argument) and renames the file into place. Once only.
  void finish(const World& sim);
  /// Ends the recording at its last stored hash (tick 0 with `initial_hash`, the state hash
  /// before the first tick, when none is stored) and renames the file into place: for a session
  /// whose current state is torn (a tick abandoned half-way by StopRequested). The ticks after
  /// that hash are dropped; they are held in memory until their hash line (at most hash_every
  /// ticks' input changes). Once only, instead of finish().
  void finish_at_last_hash(std::uint64_t initial_hash);

  [[nodiscard]] std::uint64_t ticks() const { return ticks_; }
  /// Bytes written so far (the header, tick and hash lines).
  [[nodiscard]] std::uint64_t bytes() const { return out_.size() + line_.size(); }
  /// Bytes of lines held in memory, not yet handed to the file: below 64 KiB plus hash_every
  /// ticks' lines.
  [[nodiscard]] std::uint64_t held() const { return line_.size(); }

 private:
  void flush_if_full();
  AtomicOutput out_;
  Recording head_;  ///< the header's fields, until the first tick (set_rules rewrites it)
  std::uint64_t hash_every_;
  std::uint64_t ticks_ = 0;
  bool have_last_ = false;
  TickInput last_;
  std::string line_;      ///< lines not yet handed to out_ (a few kB at most)
  std::size_t kept_ = 0;  ///< line_'s bytes up to and including the last hash line
  std::uint64_t last_hash_tick_ = 0, last_hash_ = 0;
};

}  // namespace fixstep
