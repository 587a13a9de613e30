// How the cut of a pile in two halves finds its median (DiscContacts::cut_pile()): first among
// the coordinates near the last tick's median, else among them all. Internal to the engine: not
// installed.
#pragma once

namespace fixstep::detail {

/// For tests: whether the median is sought near the last one first (the default) or always
/// among every coordinate. The same value either way (the same order statistic), so the same
/// bits.
void set_median_window(bool on);
[[nodiscard]] bool median_window();

}  // namespace fixstep::detail
