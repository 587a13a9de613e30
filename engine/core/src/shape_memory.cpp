// ShapeWorld::bytes: what a copy of the shape world holds in heap memory (World::snapshot_bytes).
#include "shape_world.hpp"

namespace fixstep::detail {

std::size_t ShapeWorld::bytes() const {
  // A copy of a vector allocates its size, not its capacity; a copy of the grid or of the
  // second thread allocates nothing (their tables are each call's own).
  auto b = [](const auto& v) { return v.size() * sizeof(v[0]); };
  return b(bodies_) + b(shapes_) + b(state_) + b(warm_) + b(kept_) + b(energy_) + b(energy_after_) +
         b(work_) + b(energy_start_) + b(dissipated_start_) + b(touched_) + b(wake_) + b(boxes_) +
         b(dynamic_) + b(pairs_) + b(order_) + b(swept_) + b(first_) + b(tags_) + b(candidates_) +
         b(unit_planes_) + b(sensor_candidates_) + b(sensed_) + b(rows_) + b(solve_) +
         b(velocity_) + b(turned_at_) + b(disabled_) + b(row_keys_) + b(statics_) + b(next_warm_) +
         b(margin_) + tree_.bytes() + b(half_rows_) + b(half_disabled_) + b(next_kept_) +
         b(half_kept_) + b(body_colors_) + b(colored_) + b(by_color_) + b(block_lanes_) +
         b(point_lanes_) + b(units_) + b(color_runs_) + b(turned_);
}

}  // namespace fixstep::detail
