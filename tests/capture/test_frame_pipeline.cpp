// FramePipeline: every frame consumed once, in order, as it was when submitted; errors stop it
// and reach the producer; the destructor finishes the queue when asked to. (Pending::drop is
// timing-dependent by nature; VideoWriter's tests cover abandoning a video.)
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "fixstep/capture/frame_pipeline.hpp"

namespace fixstep {
namespace {

using Pending = FramePipeline::Pending;

// What the worker saw: each consumed frame's tag and bytes.
struct Seen {
  std::vector<std::uint64_t> tags;
  std::vector<std::vector<std::uint8_t>> frames;
};

TEST(FramePipeline, ConsumesEveryFrameOnceInOrderAsSubmitted) {
  Seen seen;
  std::vector<std::uint8_t> frame(64);
  {
    FramePipeline p(
        frame.size(), 2,
        [&](std::span<const std::uint8_t> f, std::uint64_t tag) {
          seen.tags.push_back(tag);
          seen.frames.emplace_back(f.begin(), f.end());
        },
        Pending::consume);
    for (std::uint64_t i = 0; i < 200; ++i) {
      std::iota(frame.begin(), frame.end(), static_cast<std::uint8_t>(i));
      p.submit(frame, 1000 + i);
      frame.assign(frame.size(), 0xEE);  // the pipeline holds its own copy from here
    }
    p.drain();
    EXPECT_EQ(seen.tags.size(), 200u);  // drained: all of them, before stop
    p.stop(Pending::consume);
    EXPECT_FALSE(p.running());
  }
  ASSERT_EQ(seen.tags.size(), 200u);
  for (std::uint64_t i = 0; i < 200; ++i) {
    EXPECT_EQ(seen.tags[i], 1000 + i);
    std::vector<std::uint8_t> expected(64);
    std::iota(expected.begin(), expected.end(), static_cast<std::uint8_t>(i));
    EXPECT_EQ(seen.frames[i], expected) << "frame " << i;
  }
}

TEST(FramePipeline, TheDestructorConsumesWhatIsQueuedWhenAskedTo) {
  std::vector<std::uint64_t> tags;
  const std::vector<std::uint8_t> frame(16, 7);
  {
    FramePipeline p(
        frame.size(), 3, [&](std::span<const std::uint8_t>, std::uint64_t t) { tags.push_back(t); },
        Pending::consume);
    for (std::uint64_t i = 0; i < 10; ++i) p.submit(frame, i);
  }  // no drain(): the destructor finishes the queue
  EXPECT_EQ(tags, (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(FramePipeline, AConsumerErrorStopsItAndReachesTheProducer) {
  std::vector<std::uint64_t> tags;
  const std::vector<std::uint8_t> frame(8, 0);
  FramePipeline p(
      frame.size(), 2,
      [&](std::span<const std::uint8_t>, std::uint64_t t) {
        if (t == 3) throw std::runtime_error("disk full at frame 3");
        tags.push_back(t);
      },
      Pending::consume);
  bool thrown = false;
  for (std::uint64_t i = 0; i < 50 && !thrown; ++i) {
    try {
      p.submit(frame, i);
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "disk full at frame 3");
      thrown = true;
    }
  }
  // submit() may return before the worker reaches frame 3; drain() then reports it.
  EXPECT_THROW(p.drain(), std::runtime_error);
  EXPECT_THROW(p.submit(frame, 99), std::runtime_error);
  EXPECT_THROW(p.stop(Pending::consume), std::runtime_error);
  EXPECT_THROW(p.stop(Pending::consume), std::runtime_error);  // and again: it stays
  EXPECT_NE(p.error(), nullptr);
  EXPECT_EQ(tags, (std::vector<std::uint64_t>{0, 1, 2}));  // nothing after the failed frame
}

TEST(FramePipeline, RefusesWrongSizesAndSubmitsAfterStop) {
  const auto none = [](std::span<const std::uint8_t>, std::uint64_t) {};
  EXPECT_THROW(FramePipeline(0, 2, none, Pending::drop), std::invalid_argument);
  EXPECT_THROW(FramePipeline(16, 0, none, Pending::drop), std::invalid_argument);
  FramePipeline p(16, 2, none, Pending::drop);
  const std::vector<std::uint8_t> small(15), right(16);
  EXPECT_THROW(p.submit(small, 0), std::invalid_argument);
  p.submit(right, 0);
  p.stop(Pending::consume);
  p.stop(Pending::consume);  // idempotent
  EXPECT_EQ(p.error(), nullptr);
  EXPECT_THROW(p.submit(right, 1), std::logic_error);
}

}  // namespace
}  // namespace fixstep
