// fixstep::net: the link conditioner's decisions (fixstep/net/link_conditioner.hpp).
#include <cmath>
#include <stdexcept>

#include "fixstep/core/world_settings.hpp"
#include "fixstep/net/link_conditioner.hpp"

namespace fixstep::net {

namespace {

bool probability(double p) {
  return std::isfinite(p) && p >= 0.0 && p <= 1.0;
}
bool duration(double ms) {
  return std::isfinite(ms) && ms >= 0.0;
}

}  // namespace

LinkModel::LinkModel(const LinkSettings& settings) : s_(settings), state_(settings.seed) {
  if (!probability(s_.loss) || !probability(s_.burst_start) || !probability(s_.duplicate) ||
      !probability(s_.reorder)) {
    throw std::invalid_argument("link conditioner: a probability outside [0, 1]");
  }
  if (!duration(s_.latency_ms) || !duration(s_.jitter_ms) || !duration(s_.reorder_ms) ||
      !duration(s_.lossless_ms)) {
    throw std::invalid_argument("link conditioner: a time that is negative or not finite");
  }
  if (!std::isfinite(s_.burst_length) || s_.burst_length < 1.0) {
    throw std::invalid_argument("link conditioner: burst_length must be >= 1 datagram");
  }
}

double LinkModel::uniform() {
  // splitmix64 (Steele, Lea, Flood 2014), top 53 bits as a double in [0, 1).
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

std::vector<double> LinkModel::decide(double now_ms) {
  ++stats_.received;
  // Every draw is made for every datagram, so one setting does not shift the others' numbers.
  const double burst_draw = uniform(), loss_draw = uniform(), jitter_draw = uniform();
  const double reorder_draw = uniform(), dup_draw = uniform(), dup_jitter = uniform();
  if (in_burst_) {
    if (burst_draw < 1.0 / s_.burst_length) in_burst_ = false;
  } else if (burst_draw < s_.burst_start) {
    in_burst_ = true;
  }
  if (first_ms_ < 0.0) first_ms_ = now_ms;
  const bool lossless = now_ms - first_ms_ < s_.lossless_ms;
  if (in_burst_ && !lossless) {
    ++stats_.dropped;
    ++stats_.burst_dropped;
    return {};
  }
  if (loss_draw < s_.loss && !lossless) {
    ++stats_.dropped;
    return {};
  }
  double at = now_ms + s_.latency_ms + s_.jitter_ms * jitter_draw;
  if (reorder_draw < s_.reorder) {
    at += s_.reorder_ms;
    ++stats_.held_back;
  }
  std::vector<double> out{at};
  if (dup_draw < s_.duplicate) {
    out.push_back(at + (s_.jitter_ms + 1.0) * dup_jitter);
    ++stats_.duplicated;
  }
  stats_.delivered += out.size();
  return out;
}

}  // namespace fixstep::net
