// Names of DampingSplit (world.hpp), as scene files and the CLI spell them.
#include <optional>
#include <string_view>

#include "world_kernel.hpp"

namespace fixstep {

std::string_view damping_split_name(DampingSplit split) {
  return split == DampingSplit::per_step ? "per_step" : "per_stage";
}

std::optional<DampingSplit> parse_damping_split(std::string_view name) {
  for (DampingSplit s : {DampingSplit::per_stage, DampingSplit::per_step}) {
    if (damping_split_name(s) == name) return s;
  }
  return std::nullopt;
}

}  // namespace fixstep
