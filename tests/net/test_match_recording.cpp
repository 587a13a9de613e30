// A match's recording streamed to a file (MatchSettings::record_file): byte for byte what the
// in-memory recorder writes, in lockstep and rollback, also when the match ends early (a peer
// leaving, a desync); the bytes held in memory stay bounded over 3·10^4 ticks while the temporary
// file grows.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fixstep/io/atomic_output.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/net/desync_recording.hpp>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "net_match.hpp"

namespace fixstep::net_test {
namespace {

using net::MatchPeer;
using net::MatchSettings;
using net::MatchState;

std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A fresh directory for one test's files, removed at the end.
struct Dir {
  std::filesystem::path path;
  explicit Dir(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("fixstep_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Dir() { std::filesystem::remove_all(path); }
  Dir(const Dir&) = delete;
  Dir& operator=(const Dir&) = delete;
};

/// A host and one joiner through `link`, each streaming its recording into DIR/pI.rec and
/// keeping it in memory too when `in_memory`.
Match start_recorded(MatchSettings s, const net::LinkSettings& link, const Dir& dir,
                     bool in_memory) {
  Match m;
  const WorldDef def = billiards().def;
  s.record_in_memory = in_memory;
  s.rules_name = "test-rules";
  s.rules_version = 3;
  s.record_file = dir.path / "p0.rec";
  m.peers.push_back(
      std::make_unique<MatchPeer>(MatchPeer::host(def, s, {"127.0.0.1", 0}, TickRules{})));
  net::LinkSettings l = link;
  if (l.lossless_ms == 0.0) l.lossless_ms = lossless_handshake_ms;
  m.link = std::make_unique<net::LinkConditioner>(net::Address{"127.0.0.1", m.peers[0]->port()}, l);
  s.record_file = dir.path / "p1.rec";
  m.peers.push_back(std::make_unique<MatchPeer>(
      MatchPeer::join(def, s, {"127.0.0.1", m.link->port()}, false, TickRules{})));
  return m;
}

/// Finishes each peer's streamed recording and checks it holds every confirmed tick, byte for
/// byte format_recording of its in-memory recording. Returns the host's file's bytes.
std::string expect_streamed_equals_memory(Match& m, const Dir& dir) {
  std::string first;
  for (std::size_t i = 0; i < m.peers.size(); ++i) {
    MatchPeer& p = *m.peers[i];
    const std::filesystem::path file = dir.path / ("p" + std::to_string(i) + ".rec");
    EXPECT_FALSE(std::filesystem::exists(file)) << "published before finish_recording";
    EXPECT_TRUE(std::filesystem::exists(temporary_file_for(file)));
    EXPECT_EQ(p.finish_recording(), p.world().tick());
    EXPECT_FALSE(p.finish_recording());  // once
    EXPECT_FALSE(std::filesystem::exists(temporary_file_for(file)));
    const std::string bytes = file_bytes(file);
    EXPECT_EQ(bytes, format_recording(p.recording())) << "peer " << i;
    if (i == 0) first = bytes;
  }
  return first;
}

class MatchRecording : public ::testing::TestWithParam<std::uint16_t> {};

TEST_P(MatchRecording, IsByteForByteTheInMemoryRecordersOnEveryPeer) {
  MatchSettings s = match(2, 400);
  s.max_rollback = GetParam();
  s.input_delay = GetParam() > 0 ? 2 : 6;
  const Dir dir("match_rec_bytes");
  Match m = start_recorded(
      s, net::LinkSettings{.latency_ms = 20.0, .jitter_ms = 5.0, .loss = 0.05, .seed = 5}, dir,
      true);
  // A frame every 2 ms: a rollback peer's shown world runs ahead on predictions.
  ASSERT_TRUE(m.run(20000, {}, 2.0)) << m.describe();
  const std::string host = expect_streamed_equals_memory(m, dir);
  EXPECT_EQ(file_bytes(dir.path / "p1.rec"), host);  // the peers agree
  const Recording rec = read_recording(dir.path / "p0.rec");
  EXPECT_EQ(rec.ticks, 400u);
  EXPECT_EQ(rec.rules_name, "test-rules");
  if (GetParam() > 0) {  // predictions were made, and none of them is in the file
    EXPECT_GT(m.peers[0]->stats().predicted_ticks + m.peers[1]->stats().predicted_ticks, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(LockstepAndRollback, MatchRecording, ::testing::Values(0, 8));

TEST(MatchRecording, APeerLeavingOrADesyncKeepsEveryConfirmedTick) {
  {  // the host leaves at tick 150 of 300: the joiner fails; both keep what they confirmed
    const Dir dir("match_rec_left");
    Match m =
        start_recorded(match(2, 300), net::LinkSettings{.latency_ms = 5.0, .seed = 3}, dir, true);
    EXPECT_FALSE(m.run(20000, [&](std::size_t i) {
      if (i == 0 && m.peers[0]->world().tick() >= 150 &&
          m.peers[0]->state() == MatchState::playing) {
        m.peers[0]->leave();
      }
    }));
    m.keep_playing(300);
    EXPECT_EQ(m.peers[1]->state(), MatchState::failed);
    EXPECT_GE(m.peers[1]->world().tick(), 100u);
    EXPECT_LT(m.peers[1]->world().tick(), 300u);
    (void)expect_streamed_equals_memory(m, dir);
    World sim(billiards().def);
    EXPECT_TRUE(replay(sim, read_recording(dir.path / "p1.rec")).ok());
  }
  {  // player 1's world nudged at tick 95: both desync at tick 100's hash
    const Dir dir("match_rec_desync");
    Match m =
        start_recorded(match(2, 300), net::LinkSettings{.latency_ms = 5.0, .seed = 2}, dir, true);
    bool nudged = false;
    EXPECT_FALSE(m.run(20000, [&](std::size_t i) {
      if (i == 1 && !nudged && m.peers[1]->world().tick() >= 95) {
        World& w = m.peers[1]->world_for_test();
        w.set_velocity(w.bodies()[3], {1e-9, 0.0});
        nudged = true;
      }
    }));
    m.keep_playing(300);
    for (const auto& p : m.peers) ASSERT_EQ(p->state(), MatchState::desynced) << p->error();
    (void)expect_streamed_equals_memory(m, dir);
    World healthy(billiards().def);
    EXPECT_TRUE(replay(healthy, read_recording(dir.path / "p0.rec")).ok());
    // What net::run does without --record: the streamed file moved to a free desync name,
    // never over a file or a link.
    const std::string bytes = file_bytes(dir.path / "p1.rec");
    std::filesystem::create_symlink(dir.path / "elsewhere.rec", dir.path / "g-desync-p1-t100.rec");
    const auto moved = net::move_desync_recording(dir.path / "p1.rec", dir.path, "g", 1,
                                                  m.peers[1]->desync()->tick);
    EXPECT_EQ(moved.filename(), "g-desync-p1-t100-2.rec");
    EXPECT_EQ(file_bytes(moved), bytes);
    EXPECT_FALSE(std::filesystem::exists(dir.path / "p1.rec"));
    EXPECT_FALSE(std::filesystem::exists(dir.path / "elsewhere.rec"));
  }
}

TEST(MatchRecording, HoldsBoundedMemoryOver30000TicksWhileItsFileGrows) {
  constexpr std::uint64_t ticks = 30'000;
  MatchSettings s = match(2, ticks);
  s.hash_every = 600;
  const Dir dir("match_rec_long");
  Match m = start_recorded(s, net::LinkSettings{.seed = 4}, dir, false);
  std::uint64_t most_held = 0;
  std::uint64_t half_way_file = 0;  // the temporary file's size at tick ticks/2
  const std::filesystem::path temporary = temporary_file_for(dir.path / "p0.rec");
  ASSERT_TRUE(m.run(120000, [&](std::size_t i) {
    const MatchPeer& p = *m.peers[i];
    most_held = std::max(most_held, p.recording_bytes_held());
    if (i == 0 && half_way_file == 0 && p.world().tick() >= ticks / 2) {
      half_way_file = std::filesystem::file_size(temporary);
    }
  })) << m.describe();
  for (const auto& p : m.peers) EXPECT_THROW((void)p->recording(), std::logic_error);
  EXPECT_EQ(m.peers[0]->finish_recording(), ticks);
  const std::uint64_t size = std::filesystem::file_size(dir.path / "p0.rec");
  // A hash line a tick: about 25 bytes a tick, 750 kB in all, of which at most one flush's
  // buffer (64 KiB) and a line are ever held.
  EXPECT_GT(size, 20 * ticks);
  EXPECT_LT(most_held, 70'000u);
  EXPECT_GT(most_held, 0u);
  // Half the match's lines were in the file half-way through, less the buffer.
  EXPECT_GT(half_way_file + 70'000 + 4096, size / 2 - 30 * 10);
  EXPECT_LT(half_way_file, size);
  const Recording rec = read_recording(dir.path / "p0.rec");
  EXPECT_EQ(rec.ticks, ticks);
  EXPECT_EQ(rec.hashes.size(), ticks);
}

}  // namespace
}  // namespace fixstep::net_test
