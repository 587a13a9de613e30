// What a World holds behind its pointer (world.hpp): the kernel in the precision chosen at
// creation, the handles of its definition's bodies, the rules' random generator and the
// queries' grid; and what a WorldSnapshot holds. Internal to core: World's own sources
// (world.cpp, world_handles.cpp, world_queries.cpp) include it.
#pragma once

#include <utility>
#include <variant>
#include <vector>

#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/world.hpp"
#include "owner_ptrs.hpp"
#include "world_kernel.hpp"

namespace fixstep::detail {

/// The kernel in one of the two precisions.
using AnyKernel = std::variant<WorldKernel<float>, WorldKernel<double>>;

struct WorldState {
  AnyKernel kernel;
  std::vector<Entity> defined;             ///< World::defined_bodies()
  std::vector<Joint> defined_joints;       ///< World::defined_joints()
  Random random;                           ///< World::random()
  std::vector<StabilityFinding> warnings;  ///< World::warnings()
  /// The queries' grid: a cache, empty in a copy (world_queries.cpp: query_grid).
  mutable CachePtr<QueryGrid, QueryGridDeleter> queries;
  /// World::set_pre_solve's hook and context: not state (no snapshot holds it), handed to the
  /// kernel at each step.
  PreSolveFn pre_solve = nullptr;
  void* pre_solve_context = nullptr;
};

struct SnapshotState {
  AnyKernel kernel;
  Random random;
};

/// The queries' grid of `state`, rebuilt first when out of date (world_queries.cpp).
const QueryGrid& query_grid(const WorldState& state);

}  // namespace fixstep::detail

namespace fixstep {

template <class F>
decltype(auto) World::visit(F&& f) {
  return std::visit(std::forward<F>(f), state_->kernel);
}
template <class F>
decltype(auto) World::visit(F&& f) const {
  return std::visit(std::forward<F>(f), std::as_const(state_->kernel));
}

}  // namespace fixstep
