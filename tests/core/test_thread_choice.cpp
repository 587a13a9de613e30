// An automatic world's choice of one or two threads for its shape or disc phases
// (thread_choice.hpp), driven by given tick times: the trial's order, the rule that decides,
// the holds between trials, and the worlds that do not choose. (That either count gives the
// same bits is test_shape_threads.cpp's and test_impact_lanes.cpp's.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "thread_choice.hpp"

namespace fixstep {
namespace {

using detail::ThreadChoice;

/// Steps `choice` through `ticks` ticks of a world that chooses, each trial tick on `count`
/// threads taking time(count) seconds; returns each tick's count.
template <class Time>
std::vector<int> run(ThreadChoice& choice, int ticks, Time&& time) {
  std::vector<int> counts;
  for (int t = 0; t < ticks; ++t) {
    const int count = choice.threads(2, true);
    counts.push_back(count);
    if (choice.timing() != 0) choice.record(count, time(count));
  }
  return counts;
}

TEST(ThreadChoice, ATrialAlternatesPairsOfTwoThreadsAndOneThenHoldsItsChoice) {
  // Two threads, two, one, one, ...: only the second tick of each pair is timed.
  ThreadChoice choice;
  std::vector<int> timed;
  const auto counts =
      run(choice, ThreadChoice::trial_ticks + ThreadChoice::first_hold_ticks + 3,
          [&](int count) { return timed.push_back(count), count == 2 ? 0.5 : 1.0; });
  for (int t = 0; t < ThreadChoice::trial_ticks; ++t) {
    EXPECT_EQ(counts[t], (t / 2) % 2 == 0 ? 2 : 1) << "trial tick " << t;
  }
  // (The last is the next trial's first, on two threads.)
  ASSERT_EQ(timed.size(), std::size_t{ThreadChoice::trial_ticks / 2 + 1});
  for (std::size_t k = 0; k < timed.size(); ++k) {
    EXPECT_EQ(timed[k], k % 2 == 0 ? 2 : 1) << "timed tick " << k;
  }
  for (int t = ThreadChoice::trial_ticks;
       t < ThreadChoice::trial_ticks + ThreadChoice::first_hold_ticks; ++t) {
    EXPECT_EQ(counts[t], 2) << "held tick " << t;
  }
  // The next trial begins with two threads twice, then one.
  const int next = ThreadChoice::trial_ticks + ThreadChoice::first_hold_ticks;
  EXPECT_EQ(counts[next], 2);
  EXPECT_EQ(counts[next + 1], 2);
  EXPECT_EQ(counts[next + 2], 1);
}

TEST(ThreadChoice, TwoThreadsAreKeptOnlyWhereTheyAreFasterByTheMargin) {
  struct Case {
    double two;  // s a tick on two threads; one thread takes 1 s
    int chosen;
  };
  for (const Case c : {Case{0.5, 2}, Case{0.95, 2}, Case{0.96, 1}, Case{1.0, 1}, Case{1.9, 1}}) {
    ThreadChoice choice;
    run(choice, ThreadChoice::trial_ticks, [&](int count) { return count == 2 ? c.two : 1.0; });
    EXPECT_EQ(choice.chosen(), c.chosen) << "two threads " << c.two << " s against 1 s";
  }
}

TEST(ThreadChoice, EachCountsMedianTickDecides) {
  // One thread's ticks 1.0 s but for a preempted one of 5 s; two threads' 0.9 s but for one
  // of 0.2 s: the medians, 1.0 and 0.9, choose two threads; then two threads' ticks 1.2 s but
  // one of 0.1 s, and one thread's 1.0 s: one thread (the median, not the fastest).
  ThreadChoice choice;
  int n = 0;
  run(choice, ThreadChoice::trial_ticks, [&](int count) {
    ++n;
    if (count == 1) return n == 2 ? 5.0 : 1.0;
    return n == 3 ? 0.2 : 0.9;
  });
  EXPECT_EQ(choice.chosen(), 2);
  ThreadChoice slower;
  n = 0;
  run(slower, ThreadChoice::trial_ticks, [&](int count) {
    ++n;
    if (count == 1) return 1.0;
    return n == 5 ? 0.1 : 1.2;
  });
  EXPECT_EQ(slower.chosen(), 1);
}

TEST(ThreadChoice, EachTrialDecidesAloneAndTheHoldsDoubleToTheLongest) {
  // Two threads faster in the first trial, slower in every later one: the second trial
  // chooses one thread from its own ticks alone; the holds between trials double from
  // first_hold_ticks to hold_ticks and stay there.
  // (A trial's first timed tick is its second; a timed tick more than two after the last
  // begins a trial.)
  ThreadChoice choice;
  int trial = 0, in_trial = 0, last_timed = -100;
  std::vector<int> trial_starts;
  for (int tick = 0; tick < 3000; ++tick) {
    choice.threads(2, true);
    if (choice.timing() == 0) continue;
    if (tick - last_timed > 2) trial_starts.push_back(tick - 1), ++trial, in_trial = 0;
    last_timed = tick, ++in_trial;
    const int count = choice.timing();
    choice.record(count, count == 2 ? (trial == 1 ? 0.5 : 2.0) : 1.0);
    if (in_trial == ThreadChoice::trial_ticks / 2) {
      EXPECT_EQ(choice.chosen(), trial == 1 ? 2 : 1) << "after trial " << trial;
    }
  }
  ASSERT_GE(trial_starts.size(), 6u);
  int hold = ThreadChoice::first_hold_ticks;
  for (std::size_t k = 1; k < trial_starts.size(); ++k) {
    EXPECT_EQ(trial_starts[k] - trial_starts[k - 1], ThreadChoice::trial_ticks + hold)
        << "before trial " << k + 1;
    hold = std::min(2 * hold, ThreadChoice::hold_ticks);
  }
  EXPECT_EQ(hold, ThreadChoice::hold_ticks);
}

TEST(ThreadChoice, ATrialCutShortByAThrowLeavesNothingToTheNext) {
  // The first trial's last tick throws (a stop request): nothing decided, and its ticks (two
  // threads 0.1 s) do not count in the next trial, where two threads take 2 s and one 1 s.
  ThreadChoice choice;
  for (int t = 0; t < ThreadChoice::trial_ticks; ++t) {
    const int count = choice.threads(2, true);
    if (choice.timing() != 0 && t + 1 < ThreadChoice::trial_ticks) {
      choice.record(count, count == 2 ? 0.1 : 1.0);
    }
  }
  EXPECT_EQ(choice.chosen(), 2);  // (no trial has decided yet)
  for (int t = 0; t < ThreadChoice::first_hold_ticks; ++t) choice.threads(2, true);
  run(choice, ThreadChoice::trial_ticks, [](int count) { return count == 2 ? 2.0 : 1.0; });
  EXPECT_EQ(choice.chosen(), 1);
}

TEST(ThreadChoice, AWorldThatDoesNotChooseKeepsItsCountAndIsNotTimed) {
  ThreadChoice choice;
  EXPECT_EQ(choice.threads(2, false), 2);
  EXPECT_EQ(choice.timing(), 0);
  EXPECT_EQ(choice.threads(1, true), 1);  // one thread (a machine of one core, a wasm32 build)
  EXPECT_EQ(choice.timing(), 0);
  // Neither began a trial: the first chosen tick is the trial's first, on two threads, and
  // the second is its first timed one.
  EXPECT_EQ(choice.threads(2, true), 2);
  EXPECT_EQ(choice.timing(), 0);
  EXPECT_EQ(choice.threads(2, true), 2);
  EXPECT_EQ(choice.timing(), 2);
}

TEST(ThreadChoice, TimedReturnsThePhasesResultAndLetsItsExceptionOut) {
  ThreadChoice choice;
  choice.threads(2, true);
  EXPECT_EQ(choice.timed([] { return 42; }), 42);  // untimed
  choice.threads(2, true);
  EXPECT_EQ(choice.timed([] { return 43; }), 43);  // timed
  choice.threads(2, true);
  choice.threads(2, true);
  EXPECT_THROW(choice.timed([]() -> int { throw std::runtime_error("stop"); }), std::runtime_error);
  choice.threads(2, false);
  EXPECT_EQ(choice.timed([] { return 7; }), 7);
}

}  // namespace
}  // namespace fixstep
