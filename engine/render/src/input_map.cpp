// Bindings applied to a poll's raw events (fixstep/render/input_map.hpp).
#include "fixstep/render/input_map.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace fixstep {

namespace {

bool lists_key(const std::vector<Key>& keys, Key key) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

bool any_down(const std::vector<Key>& keys, const std::bitset<key_count>& down) {
  return std::any_of(keys.begin(), keys.end(),
                     [&](Key k) { return down[static_cast<std::size_t>(k)]; });
}

bool action_key(const InputMap& map, Key key) {
  return std::any_of(map.actions.begin(), map.actions.end(),
                     [&](const ActionBinding& a) { return lists_key(a.keys, key); });
}

/// The keys held before this poll's edges: keys_down with the edges undone, last first.
std::bitset<key_count> down_before(const UserEvents& ev) {
  std::bitset<key_count> before = ev.keys_down;
  for (auto it = ev.keys.rbegin(); it != ev.keys.rend(); ++it) {
    before[static_cast<std::size_t>(it->key)] = !it->press;
  }
  return before;
}

void apply_loop_press(const InputMap& map, Key key, UserEvents& ev) {
  for (const LoopBinding& b : map.loop) {
    if (!lists_key(b.keys, key)) continue;
    switch (b.action) {
      case LoopAction::quit:
        ev.quit = true;
        break;
      case LoopAction::pause:
        ev.toggle_pause = true;
        break;
      case LoopAction::step:
        ev.single_step = true;
        break;
      case LoopAction::faster:
        ++ev.time_scale_steps;
        break;
      case LoopAction::slower:
        --ev.time_scale_steps;
        break;
      case LoopAction::restart:
        ev.restart = true;
        break;
      case LoopAction::rewind:  // a level: below
        break;
    }
  }
}

/// The action edges of one key edge; `down` is the keys held before it, updated.
void apply_key_edge(const InputMap& map, const UserEvents::KeyEdge& edge,
                    std::bitset<key_count>& down, UserEvents& ev) {
  const auto k = static_cast<std::size_t>(edge.key);
  const bool was = down[k];
  down[k] = edge.press;
  if (was == edge.press) return;  // a repeat, or a release never pressed
  for (const ActionBinding& a : map.actions) {
    if (!lists_key(a.keys, edge.key)) continue;
    down[k] = false;
    const bool others = any_down(a.keys, down);
    down[k] = edge.press;
    if (!others) ev.edges.push_back({edge.press, a.bit});
  }
  if (edge.press && !action_key(map, edge.key)) apply_loop_press(map, edge.key, ev);
}

double axis_value(const AxisBinding& axis, const UserEvents& ev) {
  double v = (any_down(axis.positive, ev.keys_down) ? 1.0 : 0.0) -
             (any_down(axis.negative, ev.keys_down) ? 1.0 : 0.0);
  if (axis.pad) {
    const double p = ev.pad_axes[static_cast<std::size_t>(*axis.pad)];
    if (std::fabs(p) > axis.dead_zone) v = p;
  }
  return v;
}

}  // namespace

std::string_view loop_action_name(LoopAction action) {
  switch (action) {
    case LoopAction::quit:
      return "quit";
    case LoopAction::pause:
      return "pause";
    case LoopAction::step:
      return "step";
    case LoopAction::faster:
      return "faster";
    case LoopAction::slower:
      return "slower";
    case LoopAction::restart:
      return "restart";
    case LoopAction::rewind:
      return "rewind";
  }
  return "?";
}

void InputMap::apply(UserEvents& ev) const {
  ev.quit = ev.close_requested;
  ev.toggle_pause = ev.single_step = ev.restart = ev.rewind = false;
  ev.time_scale_steps = 0;
  ev.edges.clear();
  std::bitset<key_count> down = down_before(ev);
  for (const UserEvents::KeyEdge& edge : ev.keys) apply_key_edge(*this, edge, down, ev);
  for (const LoopBinding& b : loop) {
    if (b.action != LoopAction::rewind) continue;
    for (Key k : b.keys) {
      if (ev.keys_down[static_cast<std::size_t>(k)] && !action_key(*this, k)) ev.rewind = true;
    }
  }
  ev.axes_changed = 0;
  for (const AxisBinding& a : axes) {
    if (a.index >= max_axes) continue;
    const double v = axis_value(a, ev);
    if (v != ev.axes[a.index]) ev.axes_changed |= 1u << a.index;
    ev.axes[a.index] = v;
  }
}

std::optional<std::uint32_t> InputMap::action_bit(std::string_view name) const {
  for (const ActionBinding& a : actions) {
    if (a.name == name) return a.bit;
  }
  return std::nullopt;
}

std::optional<std::size_t> InputMap::axis_index(std::string_view name) const {
  for (const AxisBinding& a : axes) {
    if (a.name == name) return a.index;
  }
  return std::nullopt;
}

bool InputMap::binds(Key key) const {
  auto in = [key](const std::vector<Key>& keys) { return lists_key(keys, key); };
  return action_key(*this, key) ||
         std::any_of(axes.begin(), axes.end(),
                     [&](const AxisBinding& a) { return in(a.negative) || in(a.positive); }) ||
         std::any_of(loop.begin(), loop.end(), [&](const LoopBinding& b) { return in(b.keys); });
}

std::uint32_t InputMap::action_bits() const {
  std::uint32_t bits = 0;
  for (const ActionBinding& a : actions) bits |= a.bit;
  return bits;
}

std::string InputMap::loop_help(bool can_quit) const {
  std::string help;
  for (const LoopBinding& b : loop) {
    if (b.action == LoopAction::quit && !can_quit) continue;
    std::string keys;
    for (Key k : b.keys) {
      if (action_key(*this, k)) continue;  // the game's: not a loop key
      if (!keys.empty()) keys += '/';
      keys += key_name(k);
    }
    if (keys.empty()) continue;
    if (!help.empty()) help += "  ";
    help += keys + ' ' + std::string(loop_action_name(b.action));
  }
  return help;
}

std::optional<std::string> InputMap::problem() const {
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < actions.size(); ++i) {
    const ActionBinding& a = actions[i];
    const std::string who = "action " + std::to_string(i) + " ('" + a.name + "')";
    if (a.name.empty()) return who + ": needs a name";
    for (std::size_t j = 0; j < i; ++j) {
      if (actions[j].name == a.name)
        return who + ": the name is also action " + std::to_string(j) + "'s";
    }
    if (std::popcount(a.bit) != 1) return who + ": bit must be exactly one bit";
    if ((bits & a.bit) != 0) return who + ": its bit is another action's";
    bits |= a.bit;
    if (lists_key(a.keys, Key::none)) return who + ": binds Key::none";
  }
  std::uint32_t used = 0;
  for (const AxisBinding& a : axes) {
    const std::string who = "axis '" + a.name + "'";
    if (a.name.empty()) return std::string("an axis needs a name");
    if (a.index >= max_axes) return who + ": index must be < " + std::to_string(max_axes);
    if ((used >> a.index) & 1u) return who + ": its index is another axis's";
    used |= 1u << a.index;
    if (!(a.dead_zone >= 0.0 && a.dead_zone < 1.0)) return who + ": dead_zone must be in [0, 1)";
    if (lists_key(a.negative, Key::none) || lists_key(a.positive, Key::none)) {
      return who + ": binds Key::none";
    }
  }
  return std::nullopt;
}

std::vector<ActionBinding> default_actions() {
  return {{"left", button_left, {Key::left, Key::pad_left}},
          {"right", button_right, {Key::right, Key::pad_right}},
          {"up", button_up, {Key::up, Key::pad_up}},
          {"down", button_down, {Key::down, Key::pad_down}},
          {"action", button_action, {Key::enter, Key::keypad_enter, Key::pad_a}},
          {"pointer_primary", button_pointer_primary, {Key::mouse_left}},
          {"pointer_secondary", button_pointer_secondary, {Key::mouse_right}}};
}

std::vector<LoopBinding> default_loop_bindings() {
  return {{LoopAction::pause, {Key::space}},
          {LoopAction::step, {Key::period}},
          {LoopAction::faster, {Key::equals, Key::keypad_plus}},
          {LoopAction::slower, {Key::minus, Key::keypad_minus}},
          {LoopAction::restart, {Key::r}},
          {LoopAction::rewind, {Key::backspace}},
          {LoopAction::quit, {Key::escape}}};
}

InputMap default_input_map() {
  return {default_actions(), {}, default_loop_bindings()};
}

}  // namespace fixstep
