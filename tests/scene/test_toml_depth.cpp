// The TOML nesting bound (engine/scene/src/toml_depth.cpp): a dotted key, a
// [table] header, nested arrays or inline tables deeper than 64 levels are refused at their
// line and column before toml++ parses (a 50 000-part key overflowed its stack), in scene files
// and input scripts; strings and comments do not count; real scenes are untouched.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/scene/input_script.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {
namespace {

constexpr std::string_view head =
    "[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\n";

/// "a.a.a...a" of `parts` parts.
std::string dotted(std::size_t parts) {
  std::string key = "a";
  for (std::size_t i = 1; i < parts; ++i) key += ".a";
  return key;
}

/// The SceneError parse_scene throws for `text`, or an empty optional.
std::optional<SceneError> scene_error(const std::string& text) {
  try {
    (void)parse_scene(text, "deep.toml");
  } catch (const SceneError& e) {
    return e;
  }
  return std::nullopt;
}

bool too_deep(const std::optional<SceneError>& e) {
  return e && std::string_view(e->what()).find("nested too deep") != std::string_view::npos;
}

TEST(TomlDepth, TheIssuesFiftyThousandPartKeyIsRefusedAtItsLineNotACrash) {
  const auto e = scene_error(std::string(head) + dotted(50000) + "=1\n");
  ASSERT_TRUE(too_deep(e)) << (e ? e->what() : "no error");
  EXPECT_EQ(e->line(), 6u);
  EXPECT_EQ(e->column(), 126u);  // the dot that starts part 64 (level 65 under [[body]])
  EXPECT_NE(std::string_view(e->what()).find("level 65; fixstep allows 64"), std::string::npos)
      << e->what();
}

TEST(TomlDepth, SixtyFourLevelsAreAllowedSixtyFiveAreNot) {
  // Under [[body]] (level 1) a key of 63 parts reaches level 64: only an unknown key.
  EXPECT_FALSE(too_deep(scene_error(std::string(head) + dotted(63) + " = 1\n")));
  EXPECT_TRUE(too_deep(scene_error(std::string(head) + dotted(64) + " = 1\n")));
}

TEST(TomlDepth, TableHeadersNestedArraysAndInlineTablesCount) {
  // A header of 65 parts.
  auto e = scene_error(std::string(head) + "[" + dotted(65) + "]\n");
  ASSERT_TRUE(too_deep(e));
  EXPECT_NE(std::string_view(e->what()).find("table header"), std::string::npos);
  EXPECT_EQ(e->line(), 6u);
  // Arrays: toml++ itself stops at 256; this bound is the tighter one.
  e = scene_error(std::string(head) + "x = " + std::string(64, '[') + std::string(64, ']') + "\n");
  ASSERT_TRUE(too_deep(e));
  EXPECT_NE(std::string_view(e->what()).find("this array"), std::string::npos);
  EXPECT_EQ(e->column(), 68u);  // "x = " then 63 brackets: the 64th is at level 65
  // Inline tables, each { a = ... } one level deeper.
  std::string inline_tables = "x = ";
  for (int i = 0; i < 70; ++i) inline_tables += "{ a = ";
  inline_tables += "1" + std::string(70, '}') + "\n";
  e = scene_error(std::string(head) + inline_tables);
  ASSERT_TRUE(too_deep(e));
  EXPECT_NE(std::string_view(e->what()).find("inline table"), std::string::npos);
  // Dotted keys inside inline tables add up with the levels around them.
  std::string mixed = "x = ";
  for (int i = 0; i < 25; ++i) mixed += "{ " + dotted(3) + " = ";
  mixed += "1" + std::string(25, '}') + "\n";
  EXPECT_TRUE(too_deep(scene_error(std::string(head) + mixed)));
}

TEST(TomlDepth, StringsAndCommentsDoNotCount) {
  const std::string dots(500, '.'), brackets(500, '[');
  const std::string text = std::string(head) + "name = \"" + dots + brackets + "\"\n" + "# " +
                           dotted(500) + brackets + "\n" +    //
                           "\"" + dotted(200) + "\" = 1\n" +  // one quoted key part
                           "color = '" + brackets + "'\n" +   //
                           "x = \"\"\"\n" + brackets + "\n\"\"\"\n" + "y = '''" + dots + "'''\n";
  const auto e = scene_error(text);
  EXPECT_FALSE(too_deep(e)) << e->what();
}

TEST(TomlDepth, ARealSceneStaysWellInside) {
  // The deepest value of a scene: [[body]] → spring → anchor → its numbers (level 4).
  const std::string text = std::string(head) +
                           "spring = { anchor = [0.0, 0.0], stiffness = 1.0 }\n"
                           "[[grid]]\nname = \"g\"\ncolumns = 2\nrows = 2\n";
  EXPECT_FALSE(too_deep(scene_error(text)));
}

TEST(TomlDepth, InputScriptsAreBoundedToo) {
  const std::vector<BodyDef> bodies(1);
  const std::string script = "[[at]]\ntick = 0\n" + dotted(50000) + " = 1\n";
  try {
    (void)parse_input_script(script, "deep_script.toml", bodies);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string_view(e.what()).find("nested too deep"), std::string::npos) << e.what();
    EXPECT_EQ(e.file(), "deep_script.toml");
    EXPECT_EQ(e.line(), 3u);
  }
}

}  // namespace
}  // namespace fixstep
