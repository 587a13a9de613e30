// Bindings (fixstep/render/input_map.hpp, keys.hpp): raw key edges made into action edges, loop
// commands and axes, as the window and the browser page hand them to a game.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "fixstep/render/input_map.hpp"
#include "fixstep/render/keys.hpp"

namespace fixstep {
namespace {

constexpr std::uint32_t jump = 1u << 5, fire = 1u << 20;

InputMap game_map() {
  return {{{"jump", jump, {Key::space, Key::w, Key::pad_a}}, {"fire", fire, {Key::z}}},
          {{"walk", 1, {Key::a, Key::left}, {Key::d, Key::right}, PadAxis::left_x, 0.2}},
          default_loop_bindings()};
}

void key(UserEvents& ev, bool press, Key k) {
  ev.keys.push_back({press, k});
  ev.keys_down[static_cast<std::size_t>(k)] = press;
}

TEST(Keys, EveryKeyHasOneNameThatReadsBack) {
  for (std::size_t i = 1; i < key_count; ++i) {
    const auto k = static_cast<Key>(i);
    const std::string_view name = key_name(k);
    ASSERT_NE(name, "none");
    ASSERT_EQ(key_named(name), k) << name;
  }
  EXPECT_EQ(key_named("Z"), std::nullopt);  // names are lower case
  EXPECT_EQ(key_named("z"), Key::z);
  EXPECT_EQ(key_named("0"), Key::d0);
  EXPECT_EQ(key_named("pad_right"), Key::pad_right);
  EXPECT_EQ(pad_axis_named("trigger_right"), PadAxis::trigger_right);
}

TEST(Keys, GamepadAxisReadingsAreExactFractions) {
  EXPECT_EQ(pad_axis_value(32767), 1.0);
  EXPECT_EQ(pad_axis_value(-32767), -1.0);
  EXPECT_EQ(pad_axis_value(-32768), -1.0);  // the one reading without a positive twin
  EXPECT_EQ(pad_axis_value(0), 0.0);
  EXPECT_EQ(pad_axis_value(16384), 16384.0 / 32767.0);
}

TEST(InputMap, KeysBecomeActionEdgesInOrder) {
  const InputMap map = game_map();
  UserEvents ev;
  key(ev, true, Key::z);
  key(ev, true, Key::space);
  key(ev, false, Key::z);
  map.apply(ev);
  ASSERT_EQ(ev.edges.size(), 3u);
  EXPECT_TRUE(ev.edges[0].press && ev.edges[0].buttons == fire);
  EXPECT_TRUE(ev.edges[1].press && ev.edges[1].buttons == jump);
  EXPECT_TRUE(!ev.edges[2].press && ev.edges[2].buttons == fire);
  // Space is the game's jump: not the loop's pause.
  EXPECT_FALSE(ev.toggle_pause);
}

TEST(InputMap, AnActionIsHeldWhileAnyOfItsKeysIs) {
  const InputMap map = game_map();
  UserEvents ev;
  key(ev, true, Key::space);
  map.apply(ev);
  ASSERT_EQ(ev.edges.size(), 1u);
  ev.keys.clear();
  key(ev, true, Key::w);       // a second key of jump: no second press
  key(ev, false, Key::space);  // one still down: no release
  map.apply(ev);
  EXPECT_TRUE(ev.edges.empty());
  ev.keys.clear();
  key(ev, false, Key::w);
  map.apply(ev);
  ASSERT_EQ(ev.edges.size(), 1u);
  EXPECT_TRUE(!ev.edges[0].press && ev.edges[0].buttons == jump);
}

TEST(InputMap, LoopKeysTheActionsLeaveFree) {
  InputMap map = game_map();
  UserEvents ev;
  key(ev, true, Key::escape);
  key(ev, true, Key::period);
  key(ev, true, Key::equals);
  key(ev, true, Key::keypad_plus);
  key(ev, true, Key::minus);
  key(ev, true, Key::r);
  key(ev, true, Key::backspace);
  map.apply(ev);
  EXPECT_TRUE(ev.quit && ev.single_step && ev.restart && ev.rewind);
  EXPECT_EQ(ev.time_scale_steps, 1);
  EXPECT_TRUE(ev.edges.empty());
  // Rebound: pause on P (space was the game's).
  map.loop = {{LoopAction::pause, {Key::p}}};
  UserEvents p;
  key(p, true, Key::p);
  map.apply(p);
  EXPECT_TRUE(p.toggle_pause);
  EXPECT_EQ(map.loop_help(), "p pause");
  // The close button quits whatever the keys.
  UserEvents close;
  close.close_requested = true;
  map.apply(close);
  EXPECT_TRUE(close.quit);
}

TEST(InputMap, AxesFromKeysAndTheGamepadBeyondItsDeadZone) {
  const InputMap map = game_map();
  UserEvents ev;
  key(ev, true, Key::d);
  map.apply(ev);
  EXPECT_EQ(ev.axes[1], 1.0);
  key(ev, true, Key::left);  // both ways: 0
  map.apply(ev);
  EXPECT_EQ(ev.axes[1], 0.0);
  ev.pad_axes[static_cast<std::size_t>(PadAxis::left_x)] = 0.2;  // within the dead zone
  map.apply(ev);
  EXPECT_EQ(ev.axes[1], 0.0);
  ev.pad_axes[static_cast<std::size_t>(PadAxis::left_x)] = -0.625;  // beyond: as read
  map.apply(ev);
  EXPECT_EQ(ev.axes[1], -0.625);
  EXPECT_EQ(ev.axes[0], 0.0);  // no axis bound there
}

TEST(InputMap, DefaultsAreFixstepsButtons) {
  const InputMap map = default_input_map();
  EXPECT_EQ(map.action_bits(), all_buttons);
  EXPECT_EQ(map.action_bit("pointer_primary"), button_pointer_primary);
  EXPECT_EQ(map.problem(), std::nullopt);
  UserEvents ev;
  key(ev, true, Key::left);
  key(ev, true, Key::mouse_left);
  key(ev, true, Key::space);
  map.apply(ev);
  ASSERT_EQ(ev.edges.size(), 2u);
  EXPECT_EQ(ev.edges[0].buttons, button_left);
  EXPECT_EQ(ev.edges[1].buttons, button_pointer_primary);
  EXPECT_TRUE(ev.toggle_pause);
  EXPECT_EQ(map.loop_help(false),
            "space pause  period step  equals/keypad_plus faster  "
            "minus/keypad_minus slower  r restart  backspace rewind");
}

TEST(InputMap, ProblemsAreNamed) {
  InputMap map = game_map();
  EXPECT_EQ(map.problem(), std::nullopt);
  map.actions.push_back({"jump", 1u << 7, {Key::x}});
  EXPECT_NE(map.problem()->find("the name is also action 0's"), std::string::npos);
  map.actions.back() = {"dash", 3u, {Key::x}};
  EXPECT_NE(map.problem()->find("exactly one bit"), std::string::npos);
  map.actions.back() = {"dash", fire, {Key::x}};
  EXPECT_NE(map.problem()->find("another action's"), std::string::npos);
  map.actions.pop_back();
  map.axes.push_back({"look", 4, {}, {}, PadAxis::right_x, 0.1});
  EXPECT_NE(map.problem()->find("index must be < 4"), std::string::npos);
  map.axes.back().index = 1;
  EXPECT_NE(map.problem()->find("another axis's"), std::string::npos);
}

}  // namespace
}  // namespace fixstep
