// "Did you mean" suggestions: Levenshtein distance and the closest candidate.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fixstep/scene/suggest.hpp"

namespace fixstep {
namespace {

TEST(Suggest, EditDistanceMatchesHandCountedCases) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // Levenshtein's classic example
  EXPECT_EQ(edit_distance("stifness", "stiffness"), 1u);
  EXPECT_EQ(edit_distance("damping", "dampign"), 2u);  // a transposition is two edits
  EXPECT_EQ(edit_distance("flaw", "lawn"), 2u);
  EXPECT_EQ(edit_distance("abc", "abc"), 0u);
}

TEST(Suggest, ClosestWithinTwoEditsOrNothing) {
  const std::vector<std::string> keys = {"mass", "position", "velocity", "spring", "stiffness"};
  EXPECT_EQ(closest("stifness", keys), "stiffness");
  EXPECT_EQ(closest("positon", keys), "position");
  EXPECT_EQ(closest("colour", keys), std::nullopt);  // nothing near
  EXPECT_EQ(closest("mas", keys), "mass");
  EXPECT_EQ(closest("xyzzy", keys, 10), "mass");  // wider tolerance: the nearest wins
  EXPECT_EQ(closest("anything", std::vector<std::string>{}), std::nullopt);
}

}  // namespace
}  // namespace fixstep
