// Editing a recording's or a scene's text in the tests that check how an edit is refused.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

namespace fixstep::testing {

/// `text` with its first `from` replaced by `to`; a test failure (and `text` unchanged) when
/// `text` holds no `from`, so an edit that no longer applies cannot pass unnoticed.
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

}  // namespace fixstep::testing
