// The plane pass's first look (resolve_contacts): in a tick of planes without segments, most
// colliders are clear of every plane all the tick (plane_contact.hpp, clear_of_planes). They
// are told from the others in blocks of near_block colliders, plane by plane, so that the test
// runs on SIMD lanes, and by halves on the discs' second thread; only the others go the whole
// way (resolve_body_contacts), by halves too when they are many (a pile's bottom row). The same
// bits: a collider that the whole way finds clear keeps its integrated state, as here, and the
// bodies are independent but for the cap's count and the external work, which the second half
// leaves to this thread (PlaneTally::defer).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "disc_contacts.hpp"
#include "fixstep/core/stop_request.hpp"
#include "plane_contact.hpp"
#include "world_kernel.hpp"

namespace fixstep {

// The colliders that are not clear of every plane (clear_of_planes), into contact_.near in
// index order; the others' plane motion is "none". By halves on the discs' second thread within
// its run: half 0 runs on this thread, which polls a stop request (a StopScope's flag is seen
// on its own thread only).
template <class Real>
void detail::WorldKernel<Real>::find_near_planes() {
  const std::size_t n = contact_.body.size();
  for (auto& near : contact_.near) near.clear();
  auto pass = [&](std::size_t begin, std::size_t end, int half) {
    for (std::size_t b = begin; b < end; b += near_block) {
      if (half == 0 && b != begin && (b - begin) % 1024 == 0) {
        ++plane_polls_, throw_if_stop_requested();  // many planes: a tick of seconds
      }
      near_block_of(b, std::min(near_block, end - b), contact_.near[half]);
    }
  };
  if (discs_) {
    discs_->halves(n, pass);
  } else {
    pass(0, n, 0);
  }
}

template <class Real>
void detail::WorldKernel<Real>::near_block_of(std::size_t begin, std::size_t m,
                                              std::vector<std::uint32_t>& near) {
  using plane_contact::V2;
  const ContactScratch& c = contact_;
  const double dt = settings_.dt;
  const double rel = 8.0 * double(std::numeric_limits<Real>::epsilon());
  // Gathered into a block of fixed length (past m, the block's first body again), so that the
  // plane-by-plane loop has a constant trip count, which the compiler vectorizes. The test
  // per body and plane is clear_of_plane's, in its order of operations.
  alignas(64) double x0[near_block], y0[near_block], x1[near_block], y1[near_block];
  alignas(64) double dvx[near_block], dvy[near_block], r[near_block], scale[near_block];
  alignas(64) double clear[near_block];
  for (std::size_t i = 0; i < near_block; ++i) {
    const std::size_t k = begin + (i < m ? i : 0);
    const std::uint32_t j = c.body[k];
    const V2 a0{double(c.x0[k]), double(c.y0[k])}, a1{double(x_[j]), double(y_[j])};
    const V2 v0{double(c.vx0[k]), double(c.vy0[k])}, v1{double(vx_[j]), double(vy_[j])};
    x0[i] = a0.x, y0[i] = a0.y, x1[i] = a1.x, y1[i] = a1.y;
    dvx[i] = v1.x - v0.x, dvy[i] = v1.y - v0.y;
    r[i] = c.radius[k];
    scale[i] = plane_contact::clearance_scale(a0, a1, v0, v1, r[i], dt);
    clear[i] = 1.0;
  }
  for (const PlaneDef& p : planes_) {
    for (std::size_t i = 0; i < near_block; ++i) {
      const bool ok = plane_contact::clear_of_plane(p, V2{x0[i], y0[i]}, V2{x1[i], y1[i]},
                                                    V2{dvx[i], dvy[i]}, r[i], dt, rel, scale[i]);
      clear[i] = ok ? clear[i] : 0.0;
    }
  }
  for (std::size_t i = 0; i < m; ++i) {
    contact_.after_t[begin + i] = -1.0;
    if (clear[i] == 0.0) near.push_back(static_cast<std::uint32_t>(begin + i));
  }
}

// The near colliders the whole way, in index order: by halves on the discs' second thread
// when there are near_split or more. The first half counts into `tally` as one thread would;
// the second defers the bodies that would count against the cap or do external work, and this
// thread redoes them after the first half (the second half's others added nothing to either).
template <class Real>
void detail::WorldKernel<Real>::resolve_near_planes(PlaneTally& tally) {
  auto& near = contact_.near[0];
  auto& deferred = contact_.near[1];
  near.insert(near.end(), deferred.begin(), deferred.end());  // one list, in index order
  deferred.clear();
  PlaneTally second{.defer = true};
  auto pass = [&](std::size_t begin, std::size_t end, int half) {
    PlaneTally& t = half == 0 ? tally : second;
    for (std::size_t i = begin; i < end; ++i) {
      if (half == 0 && i % 1024 == 1023) ++plane_polls_, throw_if_stop_requested();
      resolve_body_contacts(near[i], t);
      if (t.deferred) t.deferred = false, deferred.push_back(near[i]);
    }
  };
  if (discs_ && near.size() >= near_split) {
    discs_->halves(near.size(), pass);
  } else {
    pass(0, near.size(), 0);
  }
  tally.out_of_range = tally.out_of_range || second.out_of_range;
  for (const std::uint32_t k : deferred) resolve_body_contacts(k, tally);
}

}  // namespace fixstep
