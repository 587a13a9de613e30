// Where the disc pairs' warm start is matched, and their part of a pile cut in two halves
// found: as they are gathered (a large world) or by passes of their own after the gather (a
// small one). Internal to the engine: not installed.
#pragma once

#include <cstddef>

namespace fixstep::detail {

/// Candidate pairs from which the disc pairs take their warm start as they are gathered
/// (DiscContacts::pair_contact), and their part of the split (DiscContacts::split_contacts(),
/// with the cut made before the gather): their contacts, past the caches, are then not read
/// again by DiscContacts::match_warm() nor by the split. With fewer, those passes over
/// contacts still in the cache are the cheaper (docs/perf/contact_solver_plan.md). Either way
/// the same impulses and parts: the same bits.
inline constexpr std::size_t min_gather_warm_pairs = 16384;

/// For tests: the candidate pairs from which every world matches the warm start in the gather
/// (min_gather_warm_pairs unless set; 0: always; SIZE_MAX: never).
void set_gather_warm_pairs(std::size_t pairs);
[[nodiscard]] std::size_t gather_warm_pairs();

}  // namespace fixstep::detail
