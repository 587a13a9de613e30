// Where the disc pairs' warm start is matched: as they are gathered (a large world) or by a
// pass of its own after the gather (a small one). Internal to the engine: not installed.
#pragma once

#include <cstddef>

namespace fixstep::detail {

/// Candidate pairs from which the disc pairs take their warm start as they are gathered
/// (DiscContacts::pair_contact): their contacts, past the caches, are then not read again by
/// DiscContacts::match_warm(). With fewer, match_warm()'s own pass over contacts still in the
/// cache is the cheaper (docs/perf/contact_solver_plan.md). Either way the same impulses: the
/// same bits.
inline constexpr std::size_t min_gather_warm_pairs = 16384;

/// For tests: the candidate pairs from which every world matches the warm start in the gather
/// (min_gather_warm_pairs unless set; 0: always; SIZE_MAX: never).
void set_gather_warm_pairs(std::size_t pairs);
[[nodiscard]] std::size_t gather_warm_pairs();

}  // namespace fixstep::detail
