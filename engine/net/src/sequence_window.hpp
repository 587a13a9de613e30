// Internal to fixstep::net: which of a peer's recent packet sequence numbers have arrived, so
// a replayed (duplicate) or too old packet is refused before it is used.
#pragma once

#include <cstdint>

namespace fixstep::net::detail {

class SequenceWindow {
 public:
  /// Packets this far behind the newest are refused as too old.
  static constexpr std::uint32_t size = 64;
  /// Whether `seq` is new and within the window; records it when it is.
  bool accept(std::uint32_t seq) {
    if (!any_) {
      any_ = true;
      newest_ = seq;
      seen_ = 1;
      return true;
    }
    if (seq > newest_) {
      const std::uint32_t shift = seq - newest_;
      seen_ = shift >= size ? 0 : seen_ << shift;
      seen_ |= 1;
      newest_ = seq;
      return true;
    }
    const std::uint32_t behind = newest_ - seq;
    if (behind >= size) return false;
    const std::uint64_t bit = std::uint64_t{1} << behind;
    if (seen_ & bit) return false;
    seen_ |= bit;
    return true;
  }

 private:
  bool any_ = false;
  std::uint32_t newest_ = 0;
  std::uint64_t seen_ = 0;  ///< bit k: newest_ - k arrived
};

}  // namespace fixstep::net::detail
