// Key and gamepad axis names (fixstep/render/keys.hpp).
#include "fixstep/render/keys.hpp"

#include <array>

namespace fixstep {

namespace {

constexpr std::array<std::string_view, key_count> key_names = {
#define FIXSTEP_KEY_NAME(id, name) name,
    FIXSTEP_KEYS(FIXSTEP_KEY_NAME)
#undef FIXSTEP_KEY_NAME
};

constexpr std::array<std::string_view, pad_axis_count> pad_axis_names = {
    "left_x", "left_y", "right_x", "right_y", "trigger_left", "trigger_right"};

}  // namespace

std::string_view key_name(Key key) {
  const auto i = static_cast<std::size_t>(key);
  return i < key_count ? key_names[i] : std::string_view("none");
}

std::optional<Key> key_named(std::string_view name) {
  for (std::size_t i = 1; i < key_count; ++i) {
    if (key_names[i] == name) return static_cast<Key>(i);
  }
  return std::nullopt;
}

std::string_view pad_axis_name(PadAxis axis) {
  const auto i = static_cast<std::size_t>(axis);
  return i < pad_axis_count ? pad_axis_names[i] : std::string_view("?");
}

std::optional<PadAxis> pad_axis_named(std::string_view name) {
  for (std::size_t i = 0; i < pad_axis_count; ++i) {
    if (pad_axis_names[i] == name) return static_cast<PadAxis>(i);
  }
  return std::nullopt;
}

double pad_axis_value(std::int16_t raw) {
  return raw <= -32767 ? -1.0 : static_cast<double>(raw) / 32767.0;
}

}  // namespace fixstep
