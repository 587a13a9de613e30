// The plane pass's first look (resolve_contacts): in a tick of planes without segments, most
// colliders are clear of every plane all the tick (plane_contact.hpp, clear_of_planes). They
// are told from the others in blocks of near_block colliders, plane by plane, so that the test
// runs on SIMD lanes (compiled for each SimdLevel), and by halves on the discs' second thread; only
// the others go the whole way (resolve_body_contacts), by halves too when they are many (a pile's
// bottom row). The same bits: a collider that the whole way finds clear keeps its integrated state,
// as here, and the bodies are independent but for the cap's count and the external work, which the
// second half leaves to this thread (PlaneTally::defer).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "disc_contacts.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/stop_request.hpp"
#include "plane_contact.hpp"
#include "simd_targets.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace {

/// The colliders find_near_planes tests at once.
constexpr std::size_t near_block = 64;

/// A block of colliders as near_block_of gathers them (m, m/s, s as plane_contact's), and
/// `clear`: 1 while a collider is clear of every plane tested so far, else 0.
struct NearBlock {
  alignas(64) double x0[near_block], y0[near_block], x1[near_block], y1[near_block];
  alignas(64) double dvx[near_block], dvy[near_block], r[near_block], scale[near_block];
  alignas(64) double clear[near_block];
};

/// Where a block's colliders are read from: per collider k its body, radius (m) and start
/// state (m, m/s); per body j its integrated state.
template <class Real>
struct BlockSource {
  const std::uint32_t* body;
  const double* radius;
  const Real *x0, *y0, *vx0, *vy0;
  const Real *x, *y, *vx, *vy;
};

/// Gathers colliders begin..begin+m (past m, the block's first again, so that the loops have
/// a constant trip count, which the compiler vectorizes), then tests them against every plane:
/// clear_of_plane per collider and plane, in its order of operations.
template <class Real>
[[gnu::always_inline]] inline void gather_and_test(NearBlock& b, const BlockSource<Real>& s,
                                                   std::size_t begin, std::size_t m,
                                                   std::span<const PlaneDef> planes, double dt,
                                                   double rel) {
  using plane_contact::V2;
  for (std::size_t i = 0; i < near_block; ++i) {
    const std::size_t k = begin + (i < m ? i : 0);
    const std::uint32_t j = s.body[k];
    const V2 a0{double(s.x0[k]), double(s.y0[k])}, a1{double(s.x[j]), double(s.y[j])};
    const V2 v0{double(s.vx0[k]), double(s.vy0[k])}, v1{double(s.vx[j]), double(s.vy[j])};
    b.x0[i] = a0.x, b.y0[i] = a0.y, b.x1[i] = a1.x, b.y1[i] = a1.y;
    b.dvx[i] = v1.x - v0.x, b.dvy[i] = v1.y - v0.y;
    b.r[i] = s.radius[k];
    b.scale[i] = plane_contact::clearance_scale(a0, a1, v0, v1, b.r[i], dt);
    b.clear[i] = 1.0;
  }
  for (const PlaneDef& p : planes) {
    for (std::size_t i = 0; i < near_block; ++i) {
      const bool ok =
          plane_contact::clear_of_plane(p, V2{b.x0[i], b.y0[i]}, V2{b.x1[i], b.y1[i]},
                                        V2{b.dvx[i], b.dvy[i]}, b.r[i], dt, rel, b.scale[i]);
      b.clear[i] = ok ? b.clear[i] : 0.0;
    }
  }
}

// The same block compiled for each SimdLevel (fixstep/core/simd.hpp), with internal linkage and
// everything it calls inlined (flatten), as world_step.cpp's sweeps. The tests are comparisons of
// sums and products, each rounded alone (no contraction), so every level decides the same.
template <class Real>
[[gnu::noinline]] void test_block_baseline(NearBlock& b, const BlockSource<Real>& s,
                                           std::size_t begin, std::size_t m,
                                           std::span<const PlaneDef> planes, double dt,
                                           double rel) {
  gather_and_test(b, s, begin, m, planes, dt, rel);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <class Real>
[[gnu::flatten]] FIXSTEP_TARGET_AVX2 void test_block_avx2(NearBlock& b, const BlockSource<Real>& s,
                                                          std::size_t begin, std::size_t m,
                                                          std::span<const PlaneDef> planes,
                                                          double dt, double rel) {
  gather_and_test(b, s, begin, m, planes, dt, rel);
}
template <class Real>
[[gnu::flatten]] FIXSTEP_TARGET_AVX512 void test_block_avx512(NearBlock& b,
                                                              const BlockSource<Real>& s,
                                                              std::size_t begin, std::size_t m,
                                                              std::span<const PlaneDef> planes,
                                                              double dt, double rel) {
  gather_and_test(b, s, begin, m, planes, dt, rel);
}
#endif

template <class Real>
void test_block(SimdLevel level, NearBlock& b, const BlockSource<Real>& s, std::size_t begin,
                std::size_t m, std::span<const PlaneDef> planes, double dt, double rel) {
#if FIXSTEP_HAS_SIMD_CLONES
  if (level == SimdLevel::avx512) return test_block_avx512(b, s, begin, m, planes, dt, rel);
  if (level == SimdLevel::avx2) return test_block_avx2(b, s, begin, m, planes, dt, rel);
#endif
  (void)level;
  test_block_baseline(b, s, begin, m, planes, dt, rel);
}

}  // namespace

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
  const ContactScratch& c = contact_;
  const BlockSource<Real> source{c.body.data(), c.radius.data(), c.x0.data(), c.y0.data(),
                                 c.vx0.data(),  c.vy0.data(),    x_.data(),   y_.data(),
                                 vx_.data(),    vy_.data()};
  const double rel = 8.0 * double(std::numeric_limits<Real>::epsilon());
  NearBlock b;
  test_block(simd_level(), b, source, begin, m, planes_, settings_.dt, rel);
  for (std::size_t i = 0; i < m; ++i) {
    contact_.after_t[begin + i] = -1.0;
    if (b.clear[i] == 0.0) near.push_back(static_cast<std::uint32_t>(begin + i));
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
