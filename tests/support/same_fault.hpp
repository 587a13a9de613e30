// The check of a world run on one thread and on two that both stop at a work limit: the same
// located fault (a cap is a property of the world, not of how its passes are shared).
#pragma once

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "fixstep/core/step_results.hpp"

namespace fixstep::test {

/// Expects `one` and `two` both present, naming `cap` (of `value` when given), at the same
/// tick, body, value and context.
inline void expect_same_cap_fault(const std::optional<StateFault>& one,
                                  const std::optional<StateFault>& two, const std::string& cap,
                                  std::optional<double> value = std::nullopt) {
  ASSERT_TRUE(one.has_value());
  EXPECT_EQ(one->cap, cap);
  if (value) {
    EXPECT_EQ(one->value, *value);
  }
  ASSERT_TRUE(two.has_value());
  EXPECT_EQ(two->cap, one->cap);
  EXPECT_EQ(two->tick, one->tick);
  EXPECT_EQ(two->body, one->body);
  EXPECT_EQ(two->value, one->value);
  EXPECT_EQ(two->with, one->with);
}

}  // namespace fixstep::test
