// Velocity Verlet and Forest–Ruth on a linked world: the symmetric step
//   S(h) = G(h/2) K(h/2) C↑(h/2) Dr(h) C↓(h/2) K(h/2) G(h/2)
// of link_damping.hpp (G the bodies' own exact decay, K the kick on the conservative forces,
// Dr the drift, C↑/C↓ the links' exact damping flows by ascending/descending colour), one
// stage per Verlet step and three (w1·h, w0·h, w1·h) per Forest–Ruth step. A tick's stages
// run as one chain whose adjacent kicks at the same position share one force pass (FSAL
// within the tick): per stage one loop over the links for the forces at the new positions
// (with C↓ in it), one loop for C↑ (only with damped links) and two passes over the bodies.
// Internal to the engine: not installed; used by world_coupled.cpp.
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>

#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "link_damping.hpp"
#include "link_passes.hpp"

namespace fixstep {

namespace {

/// One link damping sweep's coefficients (LinkFlow's ca, cb over some τ; null: no sweep).
template <class Real>
struct SweepFlow {
  const Real *ca = nullptr, *cb = nullptr;
  explicit operator bool() const { return ca != nullptr; }
};

/// One stage of the chain: step h, the bodies' exact decay e^{-γh/2} (null without body
/// damping), and the links' flows before its drift (C↑, `up`) and after it (C↓, `down`): both
/// over h/2 with DampingSplit::per_stage, only at the ends of a Forest–Ruth step over its
/// whole h/2 with per_step, none without link damping.
template <class Real>
struct StrangStage {
  Real h{};
  const Real* decay = nullptr;
  SweepFlow<Real> up{}, down{};
};

/// Smallest colour worth splitting between two threads (its links never share a body).
constexpr std::size_t min_parallel_colour = 1024;

/// What one kick pass of the chain applies besides the arrays (see StrangChain::kick): the
/// bodies' decay factors of the ending stage (d0) and of the next (d1), null without body
/// damping; the half steps of the two kicks, s (0 where there is none); and the weights (1 or
/// 0) of the energy the link sweeps take, counted before (C↓) and after (C↑) this kick.
/// Taken by value with restrict factors, as BodyArrays (link_passes.hpp).
template <class Real>
struct KickStep {
  const Real* __restrict d0, * __restrict d1;
  Real end_half, begin_half;
  Real swept_before, swept_after;
};

/// The kick pass of the chain for bodies [j0, j1) (see StrangChain::kick): with End, the
/// ending stage's K(h/2) then G (factor d0); with Begin, the next stage's G (factor d1) then
/// K(h/2); a = field + (1/m)·acc. A plain loop over restrict pointers (the arrays' copies
/// below) with a branch-free range check, like euler_bodies, so the compiler vectorizes it.
/// Returns true if some state is out of range (checked with End).
template <class Field, bool End, bool Begin, bool Track, bool Bracket, class Real>
bool kick_bodies(std::size_t j0, std::size_t j1, BodyArrays<Real> b, FieldArrays<Real> c,
                 KickStep<Real> s) {
  const Real* __restrict x = b.x, * __restrict y = b.y;
  Real* __restrict vx = b.vx, * __restrict vy = b.vy, * __restrict diss = b.diss;
  const Real* __restrict accx = b.accx, * __restrict accy = b.accy, * __restrict inv_m = b.inv_m;
  const Real* __restrict k = c.k, * __restrict anchor_x = c.anchor_x, * __restrict anchor_y = c.anchor_y, * __restrict rest = c.rest, * __restrict cx = c.cx, * __restrict cy = c.cy;
  const Real* __restrict d0 = s.d0, * __restrict d1 = s.d1;
  const Real push_x = c.push_x, push_y = c.push_y, end_half = s.end_half, begin_half = s.begin_half,
             swept_before = s.swept_before, swept_after = s.swept_after;
  const Real limit = static_cast<Real>(max_state_magnitude);
  Real out = 0;
  for (std::size_t j = j0; j < j1; ++j) {
    Field f;
    if constexpr (Field::shape != SpringShape::none) {
      f.k = k[j], f.anchor_x = anchor_x[j], f.anchor_y = anchor_y[j];
    }
    if constexpr (Field::shape == SpringShape::rest_length) f.rest = rest[j];
    if constexpr (Field::accel) f.cx = cx[j] + push_x, f.cy = cy[j] + push_y;
    const Real px = x[j], py = y[j];
    Real pvx = vx[j], pvy = vy[j], ax, ay;
    // The factor is read only for a damped field: d0/d1 are null otherwise.
    auto decay = [&](const Real* __restrict d) {
      if constexpr (Field::damped) {
        const Real factor = d[j];
        if constexpr (Track) diss[j] += Real(0.5) * (pvx * pvx + pvy * pvy);
        pvx *= factor, pvy *= factor;
        if constexpr (Track) diss[j] -= Real(0.5) * (pvx * pvx + pvy * pvy);
      }
    };
    f.conservative(px, py, ax, ay);
    ax += inv_m[j] * accx[j], ay += inv_m[j] * accy[j];
    // The links' damping sweeps between two kicks (C↓ before this pass, C↑ after it; a weight
    // of 0 where a stage has none): the kinetic energy they take from this body, J/kg, as the
    // difference of its ½|v|² across them.
    if constexpr (Bracket && End) diss[j] -= swept_before * (Real(0.5) * (pvx * pvx + pvy * pvy));
    if constexpr (End) {
      pvx += ax * end_half, pvy += ay * end_half;  // kick h/2
      decay(d0);
    }
    if constexpr (Begin) {
      decay(d1);
      pvx += ax * begin_half, pvy += ay * begin_half;  // kick h/2
    }
    if constexpr (Bracket && Begin) diss[j] += swept_after * (Real(0.5) * (pvx * pvx + pvy * pvy));
    vx[j] = pvx, vy[j] = pvy;
    if constexpr (End) {
      const bool in_range = (int(std::abs(px) <= limit) & int(std::abs(py) <= limit) &
                             int(std::abs(pvx) <= limit) & int(std::abs(pvy) <= limit)) != 0;
      out = in_range ? out : Real(1);
    }
  }
  return out != Real(0);
}

/// The chain of stages of one tick on the world behind Passes p (see the file comment).
template <class P, class Real>
class StrangChain {
 public:
  StrangChain(P& p, Real* accx, Real* accy, Real* nx, Real* ny)
      : p_(p), accx_(accx), accy_(accy), nx_(nx), ny_(ny) {}

  /// Runs stages stage(0) ... stage(count - 1); `cached`: the link sums and directions at the
  /// current positions are already in acc and (nx, ny) (the last tick's final pass).
  template <class Stage>
  void run(std::size_t count, Stage&& stage, bool cached) {
    if (count == 0) return;
    StrangStage<Real> s = stage(std::size_t{0});
    if (!cached) forces(nullptr);  // the tick's first position: forces only, nothing to damp
    kick(nullptr, &s);
    for (std::size_t i = 0; i < count; ++i) {
      throw_if_stop_requested();  // per stage, on the calling thread (the worker is idle here)
      if (s.up) colours<false>(s.up, true);  // C↑ at the directions of the last pass
      drift(s.h);
      forces(&s);  // forces at the new positions, with C↓(h/2) there
      if (i + 1 < count) {
        const StrangStage<Real> next = stage(i + 1);
        kick(&s, &next);
        s = next;
      } else {
        kick(&s, nullptr);
      }
    }
  }

 private:
  P& p_;
  Real *accx_, *accy_, *nx_, *ny_;

  /// Each body's sum of link forces at the current positions into acc; with a stage s of a
  /// damped network, the stage's C↓ (if any) in the same loop.
  void forces(const StrangStage<Real>* s) {
    if (!p_.net.damped) {
      p_.accumulate({p_.x, p_.y, p_.vx, p_.vy}, Real(0), accx_, accy_);
      return;
    }
    if (!s) {
      std::fill(accx_, accx_ + p_.n, Real(0)), std::fill(accy_, accy_ + p_.n, Real(0));
      colours<true>(SweepFlow<Real>{}, false);
    } else {
      colours<true>(s->down, false);  // acc zeroed by the drift
    }
  }

  /// One loop over the colours, ascending or descending: with Force, each link's spring force
  /// added to its ends' sums and its direction stored; with a stage's flow, its exact damping
  /// flow (at the direction just computed, or the stored one). The energy the flows remove is
  /// counted by the kicks around them (kick_bodies, Bracket), per body, not here per link.
  template <bool Force>
  void colours(const SweepFlow<Real>& s, bool ascending) {
    const std::size_t q = p_.net.color_offset.size() - 1;
    const bool flow = bool(s);
    for (std::size_t i = 0; i < q; ++i) {
      const std::size_t c = ascending ? i : q - 1 - i;
      const std::size_t first = p_.net.color_offset[c];
      const std::size_t count = p_.net.color_offset[c + 1] - first;
      p_.par(
          count,
          [&](std::size_t i0, std::size_t i1) {
            auto run = [&]<int Along>() {
              if (flow)
                colour<Force, true, Along>(first + i0, first + i1, s);
              else
                colour<Force, false, Along>(first + i0, first + i1, s);
            };
            // Whether a link's rest length is 0 is known for the whole network in the usual
            // cases (all or none): the loop then has no branch on it.
            if (p_.net.all_rest_length)
              run.template operator()<1>();
            else if (!p_.net.rest_length)
              run.template operator()<0>();
            else
              run.template operator()<2>();
          },
          min_parallel_colour);
    }
  }

  /// Links [i0, i1) in colour order (see colours(); Network::color_a and LinkFlow are in
  /// that order, so the loop streams them). Local copies of every pointer: the stores through
  /// Real* would otherwise make the compiler reload them per link.
  /// Along: 1 every link has a rest length (its direction matters), 0 none has, 2 mixed.
  template <bool Force, bool Flow, int Along>
  void colour(std::size_t i0, std::size_t i1, const SweepFlow<Real>& s) {
    const auto& net = p_.net;
    const std::uint32_t *ea = net.color_a.data(), *eb = net.color_b.data();
    const Real *k = net.color_k.data(), *rest = net.color_rest.data(), *x = p_.x, *y = p_.y;
    const Real *ca = s.ca, *cb = s.cb;
    Real *accx = accx_, *accy = accy_, *ux = nx_, *uy = ny_, *vx = p_.vx, *vy = p_.vy;
    for (std::size_t i = i0; i < i1; ++i) {
      const std::uint32_t a = ea[i], b = eb[i];
      const bool along = Along == 2 ? rest[i] != Real(0) : Along == 1;
      Real nx, ny;
      if constexpr (Force) {
        Real fx, fy;
        spring_force(k, rest, x, y, i, a, b, along, fx, fy, nx, ny);
        accx[a] += fx, accy[a] += fy;
        accx[b] -= fx, accy[b] -= fy;
        ux[i] = nx, uy[i] = ny;
      } else {
        nx = ux[i], ny = uy[i];
      }
      if constexpr (Flow) link_flow(a, b, along, nx, ny, ca[i], cb[i], vx, vy);
    }
  }

  /// Drift x += v h (and zero the sums for the next force pass).
  void drift(Real h) {
    const bool zero = p_.net.damped;
    p_.par(p_.n, [&](std::size_t j0, std::size_t j1) {
      for (std::size_t j = j0; j < j1; ++j) p_.x[j] += p_.vx[j] * h, p_.y[j] += p_.vy[j] * h;
      if (zero)
        std::fill(accx_ + j0, accx_ + j1, Real(0)), std::fill(accy_ + j0, accy_ + j1, Real(0));
    });
  }

  /// At one position, stage `end`'s closing K(h/2) G(h/2) and stage `begin`'s opening
  /// G(h/2) K(h/2) (either may be null), on the field plus the link sums.
  void kick(const StrangStage<Real>* end, const StrangStage<Real>* begin) {
    // The kinetic energy the link sweeps take is counted around them (kick_bodies): from the
    // closing stage's C↓, ending at this kick, and into the opening stage's C↑, starting here.
    const KickStep<Real> step{.d0 = end ? end->decay : nullptr,
                              .d1 = begin ? begin->decay : nullptr,
                              .end_half = end ? end->h * Real(0.5) : Real(0),
                              .begin_half = begin ? begin->h * Real(0.5) : Real(0),
                              .swept_before = end && end->down ? Real(1) : Real(0),
                              .swept_after = begin && begin->up ? Real(1) : Real(0)};
    // The work of static and kinematic ends through their links' springs, at this position
    // with the kicks' weights (the trapezoid of the step's two kicks; their dampers' share is
    // in the damping flows' account: World::external_work()).
    if (!p_.net.driven.empty()) {
      p_.template drive_links<false>({p_.x, p_.y, p_.vx, p_.vy},
                                     double(step.end_half + step.begin_half));
    }
    const BodyArrays<Real> body = p_.body_arrays(accx_, accy_);
    const FieldArrays<Real> field = p_.field_arrays();
    with_field<Real, 0>(p_.shape, p_.c.damping, p_.accel, [&](auto f) {
      using Field = decltype(f);
      p_.par(p_.n, [&](std::size_t j0, std::size_t j1) {
        auto run = [&]<bool End, bool Begin, bool Track, bool Bracket>() {
          return kick_bodies<Field, End, Begin, Track, Bracket>(j0, j1, body, field, step);
        };
        auto tracked = [&]<bool End, bool Begin>() {
          if (!p_.track) return run.template operator()<End, Begin, false, false>();
          return p_.net.damped ? run.template operator()<End, Begin, true, true>()
                               : run.template operator()<End, Begin, true, false>();
        };
        const bool out = !end     ? tracked.template operator()<false, true>()
                         : !begin ? tracked.template operator()<true, false>()
                                  : tracked.template operator()<true, true>();
        p_.flag(out);
      });
    });
  }
};

}  // namespace

}  // namespace fixstep
