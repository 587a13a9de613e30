// The limits of one command (command_limits.hpp).
#include "fixstep/io/command_limits.hpp"

#include <fmt/format.h>

namespace fixstep {

void check_command_work(std::uint64_t ticks, std::uint64_t work_per_tick, std::string_view what) {
  if (ticks > max_command_ticks) {
    throw LimitError(fmt::format("{}: {} ticks; a command may step at most {:.0e} ticks", what,
                                 ticks, double(max_command_ticks)));
  }
  if (work_per_tick > 0 && ticks > max_command_work / work_per_tick) {
    throw LimitError(fmt::format(
        "{}: {} ticks × {} body-substeps per tick = {:.3g} body-substeps; a command may do at "
        "most {:.0e} (about a day of CPU): step fewer ticks or a smaller world",
        what, ticks, work_per_tick, double(ticks) * double(work_per_tick),
        double(max_command_work)));
  }
}

}  // namespace fixstep
