// World::snapshot_bytes: what a copy of a world costs in heap memory.
#include <cstddef>
#include <string>
#include <vector>

#include "copy_bytes.hpp"
#include "disc_contacts.hpp"
#include "shape_world.hpp"
#include "sparse_set.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return detail::copy_bytes(v);
}
std::size_t bytes_of(const std::vector<std::string>& names) {
  const std::size_t in_place = std::string().capacity();  // the short-string buffer
  std::size_t n = names.size() * sizeof(std::string);
  for (const std::string& s : names) n += s.size() > in_place ? s.size() + 1 : 0;
  return n;
}
std::size_t bytes_of(const detail::SparseSet& s) {
  return bytes_of(s.sparse) + bytes_of(s.dense);
}
template <class C>
std::size_t bytes_of(const detail::Store<C>& s) {
  return bytes_of(s.set) + bytes_of(s.data);
}
template <class... Parts>
std::size_t sum(const Parts&... parts) {
  return (bytes_of(parts) + ...);
}

}  // namespace

template <class Real>
std::size_t detail::WorldKernel<Real>::snapshot_bytes() const {
  std::size_t n = sum(generations_, free_slots_, link_generations_, link_free_slots_, bodies_, x_,
                      y_, vx_, vy_, prev_x_, prev_y_, mass_, types_, names_, user_data_);
  n += sum(springs_, constant_forces_, gravities_, drags_, appearances_, colliders_, links_,
           link_defs_, dissipated_body_, dissipated_link_, planes_, segment_found_, angle_, spin_,
           inv_inertia_);
  n += segments_.bytes();
  n += sum(coeff_.stiffness, coeff_.anchor_x, coeff_.anchor_y, coeff_.rest, coeff_.gamma,
           coeff_.accel_x, coeff_.accel_y, flows_);
  for (const DampingFlow& f : flows_) n += bytes_of(f.decay);
  n += sum(net_.a, net_.b, net_.k, net_.damping, net_.rest, net_.inv_mass, net_.offset,
           net_.incident, net_.driven, net_.color_offset, net_.by_color, net_.color_a, net_.color_b,
           net_.color_k, net_.color_rest, fx_, fy_, power_body_, power_link_, link_flows_, unit_x_,
           unit_y_, fsal_x_, fsal_y_);
  for (const LinkFlow& f : link_flows_) n += sum(f.ca, f.cb);
  for (std::size_t i = 0; i < s_.size(); ++i) n += bytes_of(s_[i]) + bytes_of(d_[i]);
  n += sum(contact_.body, contact_.radius, contact_.x0, contact_.y0, contact_.vx0, contact_.vy0,
           contact_.after_t, contact_.after, contact_.near[0], contact_.near[1]);
  n += sum(immovable_.body, immovable_.x0, immovable_.y0, immovable_.vx0, immovable_.vy0,
           immovable_.d0);
  n += sum(still_ticks_, asleep_, disc_of_, kinematic_discs_, island_next_, island_parent_,
           island_blocked_, wake_bodies_, flip_scratch_, shaped_dynamic_, kinematic_shaped_);
  n += sum(touching_, asleep_touching_, touching_before_, hits_, begun_, ended_, begun_half_,
           ended_half_, impacts_, saved_accel_);
  n += sum(sensed_, sensed_before_, sensor_crossed_, sensor_begun_, sensor_ended_);
  if (discs_) n += sizeof(*discs_.get()) + discs_->bytes();
  n += sum(plane_work_, awake_.bodies, awake_.colliders, awake_.flipped, run_scratch_.woke,
           run_scratch_.slept, run_scratch_.woke_slots, run_scratch_.slept_slots, run_scratch_.runs,
           push_saved_, push_saved_implicit_);
  // Bodies with shapes, and their contacts' state and scratch.
  n += sum(shape_sets_);
  for (const ShapeSet& set : shape_sets_.data) n += bytes_of(set.defs);
  if (shape_world_) n += sizeof(*shape_world_.get()) + shape_world_->bytes();
  // Joints and character movers.
  n += sum(joints_, joint_generations_, joint_free_slots_, joint_records_, joint_handles_,
           joint_unpaired_, joint_unpaired_start_, joints_broken_, movers_, mover_obstacles_,
           mover_segments_, mover_slide_.contacts_);
  return n;
}

}  // namespace fixstep
