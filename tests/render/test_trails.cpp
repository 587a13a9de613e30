// Trails keyed by body handle, as data: which samples belong to which handle, frames without
// ids, and no allocation once warm (counted by count_new.cpp, so no rendering here: Mesa's
// llvmpipe and a replaced operator new do not mix under AddressSanitizer). The drawn side is
// test_trail_frames.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "fixstep/detail/defined_entity.hpp"
#include "fixstep/render.hpp"
#include "fixstep/trails.hpp"

extern std::atomic<bool> counting;              // count_new.cpp
extern std::atomic<std::size_t> counted_bytes;  // bytes asked for while counting

namespace fixstep {
namespace {

// --- Trails alone: which samples belong to which handle ----------------------------------------

RenderFrame frame_of(std::vector<Entity> ids, float x) {
  RenderFrame f;
  f.ids = std::move(ids);
  f.x.assign(f.ids.size(), x);
  f.y.assign(f.ids.size(), 0.0f);
  return f;
}

int count_of(const Trails& t, std::size_t j) {
  std::array<float, Trails::capacity> xs, ys;
  return t.samples(j, xs, ys);
}

TEST(Trails, ATrailBelongsToItsHandleNotToItsIndexOrSlot) {
  const Entity a{1, 1}, b{2, 1}, b2{2, 2}, c{3, 1};
  Trails t;
  for (int f = 0; f < 50; ++f) t.record(frame_of({a, b}, float(f)));
  EXPECT_EQ(count_of(t, 0), Trails::capacity);  // capped at 45 samples
  // b destroyed and c created: c (now at b's index) starts afresh, a keeps its trail.
  t.record(frame_of({a, c}, 50.0f));
  EXPECT_EQ(count_of(t, 0), Trails::capacity);
  EXPECT_EQ(count_of(t, 1), 1);
  // b's slot reused with a new generation: a new body, although its slot had a trail before.
  t.record(frame_of({b2, a, c}, 51.0f));
  EXPECT_EQ(count_of(t, 0), 1);
  EXPECT_EQ(count_of(t, 1), Trails::capacity);
  EXPECT_EQ(count_of(t, 2), 2);
  // Samples are oldest first, in m: a's last three are 49, 50, 51.
  std::array<float, Trails::capacity> xs, ys;
  ASSERT_EQ(t.samples(1, xs, ys), Trails::capacity);
  EXPECT_EQ(xs[Trails::capacity - 3], 49.0f);
  EXPECT_EQ(xs[Trails::capacity - 1], 51.0f);
  // A body absent from one record (destroyed; its handle back only through a rewind) starts
  // afresh; clear() restarts every trail.
  t.record(frame_of({a}, 52.0f));
  t.record(frame_of({a, c}, 53.0f));
  EXPECT_EQ(count_of(t, 1), 1);
  t.clear();
  t.record(frame_of({a, c}, 54.0f));
  EXPECT_EQ(count_of(t, 0), 1);
  EXPECT_EQ(count_of(t, 1), 1);
}

TEST(Trails, AFrameWithoutIdsKeysBodiesByIndexAndBadIdsAreRefused) {
  Trails t;
  RenderFrame f;
  f.x = {0.0f, 1.0f};
  f.y = {0.0f, 0.0f};
  t.record(f);
  t.record(f);
  EXPECT_EQ(count_of(t, 1), 2);
  f.ids = {Entity{1, 1}};
  EXPECT_THROW(t.record(f), std::invalid_argument);  // 1 id for 2 bodies
  f.ids = {Entity{1, 1}, null_entity};
  EXPECT_THROW(t.record(f), std::invalid_argument);
}

TEST(Trails, RecordingAllocatesNothingOnceWarm) {
  // 10^4 bodies, steady, then 100 of them replaced by new bodies in the freed slots.
  std::vector<Entity> ids(10000);
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = detail::defined_entity(i);
  RenderFrame f = frame_of(ids, 0.0f);
  Trails t;
  t.record(f);
  counting = true;
  counted_bytes = 0;
  t.record(f);
  for (std::size_t i = 0; i < 100; ++i) f.ids[i * 7].generation = 2;
  t.record(f);
  counting = false;
  EXPECT_EQ(counted_bytes, 0u);
  EXPECT_EQ(count_of(t, 7), 1);
  EXPECT_EQ(count_of(t, 8), 3);
}

}  // namespace
}  // namespace fixstep
