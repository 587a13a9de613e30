// Sensor events: which discs began and stopped overlapping a sensor in a tick, from the
// sensors' overlaps after the tick (disc_sensors.cpp) and before it. O(overlaps) per tick, only
// in worlds with sensors; no allocation once warm.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "disc_contacts.hpp"
#include "shape_world.hpp"
#include "sorted_diff.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace {

bool sensor_order(const SensorEvent& l, const SensorEvent& r) {
  if (l.sensor.slot() != r.sensor.slot()) return l.sensor.slot() < r.sensor.slot();
  return l.visitor.slot() < r.visitor.slot();
}

void sort_sensor_events(std::vector<SensorEvent>& list) {
  if (!std::is_sorted(list.begin(), list.end(), sensor_order)) {
    std::sort(list.begin(), list.end(), sensor_order);
  }
}

}  // namespace

template <class Real>
void detail::WorldKernel<Real>::check_sensor(const Collider& c, const std::string& who) const {
  if (c.sensor && !settings_.contacts) {
    throw std::invalid_argument(
        fmt::format("{}: collider.sensor needs disc contacts (WorldSettings::contacts; a scene's "
                    "[contacts] table): without them no sensor would ever see a disc",
                    who));
  }
}

template <class Real>
void detail::WorldKernel<Real>::update_sensor_events(bool discs) {
  sensed_before_.swap(sensed_);
  sensed_.clear(), sensor_crossed_.clear(), sensor_begun_.clear(), sensor_ended_.clear();
  const std::span<const Entity> ids = bodies_.dense;
  if (discs) {
    for (const detail::SensorOverlap& o : discs_->sensed()) {
      const SensorEvent e{ids[o.sensor], ids[o.visitor]};
      (o.crossed ? sensor_crossed_ : sensed_).push_back(e);
    }
  }
  if (shape_world_) {  // sensor shapes, at the tick's end (world_shapes.cpp)
    const ShapeWorld& w = *shape_world_;
    for (const ShapeWorld::Sensed& o : w.sensed()) {
      sensed_.push_back({ids[w.bodies_[o.sensor].body], ids[w.bodies_[o.visitor].body]});
    }
  }
  if (sensed_.empty() && sensed_before_.empty() && sensor_crossed_.empty()) return;
  sort_sensor_events(sensed_);
  // Both lists sorted by slots: one merge finds what began and what ended.
  detail::sorted_diff<SensorEvent>(
      sensed_, sensed_before_, sensor_order,
      [](const SensorEvent& l, const SensorEvent& r) { return l == r; },
      [&](const SensorEvent& e) { sensor_begun_.push_back(e); },
      [&](const SensorEvent& e) { sensor_ended_.push_back(e); });
  if (!sensor_crossed_.empty()) {  // in and out within the tick: begun and ended at once
    for (const SensorEvent& e : sensor_crossed_) {
      sensor_begun_.push_back(e);
      // One moved out between ticks (set_position) before crossing has ended above: once.
      if (!std::binary_search(sensed_before_.begin(), sensed_before_.end(), e, sensor_order)) {
        sensor_ended_.push_back(e);
      }
    }
    sort_sensor_events(sensor_begun_), sort_sensor_events(sensor_ended_);
  }
}

}  // namespace fixstep
