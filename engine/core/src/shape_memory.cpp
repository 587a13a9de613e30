// ShapeWorld::bytes: what a copy of the shape world holds in heap memory (World::snapshot_bytes).
#include "copy_bytes.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

std::size_t ShapeWorld::bytes() const {
  // A copy of the grid or of the second thread allocates nothing (their tables are each
  // call's own).
  return copy_bytes(bodies_, shapes_, state_, warm_, kept_, energy_, energy_after_, work_,
                    energy_start_, dissipated_start_, touched_, wake_, boxes_, dynamic_, pairs_,
                    order_, swept_, first_, tags_, candidates_, unit_planes_, sensor_candidates_,
                    sensed_, rows_, solve_, velocity_, turned_at_, push_split_.side,
                    push_split_.rows, push_split_.moved_at, disabled_, row_keys_, near_segments_,
                    near_statics_, next_warm_, margin_, half_rows_, half_disabled_, next_kept_,
                    half_kept_, body_colors_, colored_, by_color_, block_lanes_, point_lanes_,
                    units_, color_runs_, color_kinds_, color_places_, turned_, fresh_arms_, fast_,
                    tree_active_) +
         tree_.bytes() + halves_.bytes() + joint_bodies_.bytes() + limit_rows_.bytes() +
         limit_shifts_.bytes() + point_rows_.bytes() +
         keep_search_.bytes();  // (conjugate_'s copy holds nothing)
}

}  // namespace fixstep::detail
