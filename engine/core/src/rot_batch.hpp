// Rotations of many angles at once (the shape phase's passes over its moving bodies): the same
// bits as rot_of for each, their sines and cosines four at a time (det_trig_lanes.hpp).
// Internal: not installed.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "det_trig_lanes.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/simd.hpp"
#include "shape_geom.hpp"

namespace fixstep::detail {

/// Rotations asked for by id and made a batch at a time: add(id, angle, store) keeps the
/// angle and, once `size` are kept, calls store(id, rot_of(angle)) for each kept (in the order
/// added); flush(store) does so for those left. Throws nothing: a NaN or infinite angle gives
/// NaN in both, as rot_of. One batch per thread (it holds the batch on the stack: 1.8 KB).
class RotBatch {
 public:
  static constexpr std::size_t size = 64;

  template <class Store>
  void add(std::uint32_t id, double angle, Store&& store) {
    ids_[count_] = id, angles_[count_] = angle;
    beyond_ = beyond_ || !(std::abs(angle) <= det::trig_max_argument);  // (NaN too: rare)
    if (++count_ == size) flush(store);
  }

  template <class Store>
  void flush(Store&& store) {
    if (beyond_) {
      for (std::size_t i = 0; i < count_; ++i) angles_[i] = trig_angle(angles_[i]);
      beyond_ = false;
    }
    det::sincos_each({angles_.data(), count_}, sines_, cosines_, level_);
    for (std::size_t i = 0; i < count_; ++i) store(ids_[i], Rot{cosines_[i], sines_[i]});
    count_ = 0;
  }

 private:
  SimdLevel level_ = simd_level();
  std::size_t count_ = 0;
  bool beyond_ = false;  ///< some angle kept is beyond det's trig range, or not a number
  std::array<std::uint32_t, size> ids_;
  std::array<double, size> angles_, sines_, cosines_;
};

/// store(id, rot_of(angle(id))) for each id of `ids`, in batches (RotBatch).
template <class Ids, class Angle, class Store>
void rot_of_each(const Ids& ids, Angle&& angle, Store&& store) {
  RotBatch batch;
  for (const std::uint32_t id : ids) batch.add(id, angle(id), store);
  batch.flush(store);
}

}  // namespace fixstep::detail
