// SequenceWindow (engine/net/src/sequence_window.hpp, internal): which of a peer's recent
// unreliable sequence numbers have arrived. A new one is taken once; a replay, or one 64 or
// more behind the newest, is refused; a jump forward of 64 or more forgets the older ones.
#include <gtest/gtest.h>

#include <cstdint>

#include "sequence_window.hpp"

namespace fixstep::net_test {
namespace {

using net::detail::SequenceWindow;

TEST(SequenceWindow, TakesEachNumberOnceInAnyOrderWithinTheWindow) {
  SequenceWindow w;
  EXPECT_TRUE(w.accept(10));  // the first, whatever it is
  EXPECT_FALSE(w.accept(10));
  EXPECT_TRUE(w.accept(12));
  EXPECT_TRUE(w.accept(11));  // late, not seen: taken
  EXPECT_FALSE(w.accept(11));
  EXPECT_FALSE(w.accept(12));
  EXPECT_TRUE(w.accept(0));  // 12 behind
  EXPECT_FALSE(w.accept(0));
}

TEST(SequenceWindow, RefusesNumbersTheWindowSizeOrMoreBehindTheNewest) {
  static_assert(SequenceWindow::size == 64);
  SequenceWindow w;
  EXPECT_TRUE(w.accept(100));
  EXPECT_FALSE(w.accept(36));  // 64 behind: out
  EXPECT_FALSE(w.accept(0));
  EXPECT_TRUE(w.accept(37));  // 63 behind: the oldest still in
  EXPECT_FALSE(w.accept(37));
  // The window moves with the newest: 37 is now 64 behind 101, refused even had it not come.
  SequenceWindow v;
  EXPECT_TRUE(v.accept(100));
  EXPECT_TRUE(v.accept(101));
  EXPECT_FALSE(v.accept(37));
  EXPECT_TRUE(v.accept(38));
}

TEST(SequenceWindow, AJumpForwardOfTheWindowOrMoreForgetsWhatCameBefore) {
  SequenceWindow w;
  for (std::uint32_t s = 0; s < 10; ++s) EXPECT_TRUE(w.accept(s));
  EXPECT_TRUE(w.accept(9 + 64));  // the old ones are all out of the window now
  EXPECT_FALSE(w.accept(9));
  EXPECT_TRUE(w.accept(10));  // 63 behind, never seen
  EXPECT_TRUE(w.accept(1000));
  EXPECT_TRUE(w.accept(999));
  EXPECT_FALSE(w.accept(1000 - 64));
  // Near the top of the counter, nothing wraps.
  SequenceWindow top;
  EXPECT_TRUE(top.accept(0xffffffffu));
  EXPECT_FALSE(top.accept(0xffffffffu));
  EXPECT_TRUE(top.accept(0xffffffffu - 63));
  EXPECT_FALSE(top.accept(0xffffffffu - 64));
  EXPECT_FALSE(top.accept(0));
}

}  // namespace
}  // namespace fixstep::net_test
