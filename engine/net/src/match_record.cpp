// fixstep::net: a match's recording: each confirmed tick recorded (in memory, streamed to its
// file, or both), and the recording taken or finished (fixstep/net/match_peer.hpp).
#include <stdexcept>

#include "fixstep/core/limits.hpp"
#include "match_peer_impl.hpp"

namespace fixstep::net {

void MatchPeer::Impl::record_tick(const TickInput& merged) {
  if (recorder) recorder->record(merged, *world);
  if (!writer) return;
  writer->record(merged, *world);
  // Near the most a recording may hold (max_recording_bytes, what a replay reads): the file is
  // finished here, whole, rather than refused at the end; the match plays on unrecorded. The
  // margin is far more than one tick's lines.
  constexpr std::uint64_t margin = std::uint64_t{1} << 20;
  if (writer->bytes() + margin > max_recording_bytes) {
    recording_cut = writer->ticks();
    writer->finish(*world);
    writer.reset();
  }
}

Recording MatchPeer::recording() const {
  if (!impl_->recorder) {
    throw std::logic_error(impl_->settings.record_in_memory
                               ? "MatchPeer::recording: the match never started"
                               : "MatchPeer::recording: not kept in memory (record_in_memory)");
  }
  Recorder copy = *impl_->recorder;
  return copy.finish(*impl_->world);
}

std::optional<std::uint64_t> MatchPeer::finish_recording() {
  Impl& m = *impl_;
  if (m.recording_taken) return std::nullopt;
  if (m.recording_cut) {
    m.recording_taken = true;
    return m.recording_cut;
  }
  if (!m.writer || m.players == 0) return std::nullopt;  // never started: removed with the peer
  m.recording_taken = true;
  const std::uint64_t ticks = m.writer->ticks();
  // Only confirmed ticks are recorded, and each is whole (the world is between two ticks).
  m.writer->finish(*m.world);
  m.writer.reset();
  return ticks;
}

std::optional<std::uint64_t> MatchPeer::recording_cut() const {
  return impl_->recording_cut;
}

std::uint64_t MatchPeer::recording_bytes_held() const {
  return impl_->writer ? impl_->writer->held() : 0;
}

}  // namespace fixstep::net
