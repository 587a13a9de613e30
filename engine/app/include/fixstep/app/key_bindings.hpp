// What every fixstep loop does with its user's events (fixstep/render/user_events.hpp): the loop
// keys (pause, single step, time scale) applied to the FixedStepLoop, the tick-input part (button
// edges, pointer) handed to the InputSampler, and the held arrow buttons as a push.
#pragma once

#include <cstdint>
#include <string_view>

#include "fixstep/core/input.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/core/types.hpp"
#include "fixstep/render/render.hpp"
#include "fixstep/render/user_events.hpp"

namespace fixstep {

/// The loop keys' help line for the HUD (Session::set_key_help): a window's, with Esc to quit,
/// and a web page's, which a page cannot quit.
inline constexpr std::string_view window_key_help =
    "space pause  . step  +/- speed  r restart  arrows push  mouse drag  backspace rewind  esc "
    "quit";
inline constexpr std::string_view page_key_help =
    "space pause  . step  +/- speed  r restart  arrows push  mouse drag  backspace rewind";

/// Hands the tick-input part of `ev` to `sampler`: every action edge in order, the axes, and
/// the pointer converted to world metres through `camera` for a width x height frame
/// (screen_to_world).
void feed(const UserEvents& ev, InputSampler& sampler, const Camera& camera, int width, int height);

/// Applies the loop keys of `ev` to `loop`, the same in every fixstep loop: space toggles
/// pause; '.' pauses and runs exactly one tick on the next advance(); each '+' doubles and each
/// '-' halves the time scale, kept within [1/16, max_time_scale]. Quit, restart and the arrow
/// keys are left to the caller (what they reset or push differs per program).
void apply_loop_keys(const UserEvents& ev, FixedStepLoop& loop, double max_time_scale = 16.0);

/// The push acceleration (m/s²) of the held arrow buttons (`held`, InputButton bits): half a
/// view width (`view_width`, m) per s² along each held axis, visible at any scene scale.
[[nodiscard]] Vec2 arrow_push(std::uint32_t held, double view_width);

}  // namespace fixstep
