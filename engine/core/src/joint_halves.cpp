// The joints by halves on two threads (joint_halves.hpp): groups by shared bodies, halves by
// count.
#include "joint_halves.hpp"

#include <numeric>

#include "copy_bytes.hpp"
#include "island_union.hpp"

namespace fixstep::detail {

bool JointHalves::split(std::span<const JointRecord> joints, std::span<const std::uint32_t> listed,
                        const JointBodies& numbered) {
  constexpr std::uint32_t none = JointRecord::none;
  const std::size_t bodies = numbered.size();
  auto at = [&](std::uint32_t body) { return numbered.local(body); };
  root_.resize(bodies);
  std::iota(root_.begin(), root_.end(), 0U);
  std::uint32_t total = 0;
  for (const std::uint32_t i : listed) {
    const JointRecord& j = joints[i];
    if (j.broken) continue;
    ++total;
    if (j.a != none && j.b != none) join(root_, at(j.a), at(j.b));
  }
  count_.assign(bodies, 0);
  half_of_.assign(bodies, unset);
  // A joint to the world alone at both ends holds no body: a group of its own, kept in the
  // first half (it moves nothing).
  auto group = [&](const JointRecord& j) { return find_root(root_, at(j.a != none ? j.a : j.b)); };
  for (const std::uint32_t i : listed) {
    const JointRecord& j = joints[i];
    if (!j.broken && (j.a != none || j.b != none)) ++count_[group(j)];
  }
  joints_[0].clear(), joints_[1].clear();
  std::uint32_t first = 0;  // the joints of the groups given to the first half so far
  for (const std::uint32_t i : listed) {
    const JointRecord& j = joints[i];
    if (j.broken) continue;
    std::uint32_t half = 0;
    if (j.a != none || j.b != none) {
      std::uint32_t& h = half_of_[group(j)];
      if (h == unset) {
        h = 2 * first < total ? 0U : 1U;
        if (h == 0) first += count_[group(j)];
      }
      half = h;
    }
    joints_[half].push_back(i);
  }
  half_of_body_.assign(bodies, 0);
  for (std::uint32_t k = 0; k < bodies; ++k) {
    const std::uint32_t h = half_of_[find_root(root_, k)];
    if (h != unset) half_of_body_[k] = static_cast<std::uint8_t>(h);
  }
  return !joints_[0].empty() && !joints_[1].empty();
}

std::size_t JointHalves::bytes() const {
  return copy_bytes(root_, count_, half_of_, half_of_body_, joints_[0], joints_[1]);
}

}  // namespace fixstep::detail
