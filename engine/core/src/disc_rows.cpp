// Disc contacts, phase 2: the velocity iterations' and the push-out's own copies of what they
// read and write. The contacts in solving order (order_) become rows of the fields an impulse
// needs, and the discs they move are slots in one array of velocities, disc k at slot 3 + k: a
// sweep then reads and writes one compact array, and never a position (an impulse acts as a
// constant force over the tick, so a disc's position changes by κ dt times its velocity's
// change: scatter_rows() moves it once, after the sweeps). A static disc, a plane or a still
// segment is the velocity-0 slot of the row's part (slots 0, 1, 2); a moving kinematic
// partner gets a slot of its own per row, past the discs'. No slot is written by both threads,
// and the two halves' rows are built and scattered on the two threads (on one when a row has a
// moving kinematic partner: its slot is appended). Each row's warm start is applied as the row
// is made. The push-out's rows hold what it needs of a contact and nothing else, in the same
// order.
#include <cassert>

#include "disc_contacts.hpp"

namespace fixstep::detail {

template <class Real>
void DiscContacts<Real>::set_slots() {
  const std::size_t n = discs_.size(), m = contacts_.size();
  // Where the contacts are at least half as many as the discs (a pile) the slots are set by
  // disc, in disc order, else (a gas, where few discs touch) by contact.
  auto set_slot = [&](std::uint32_t k) {
    sv_[3 + k] = {evx_[k], evy_[k]};
    if (rolling_) sw_[3 + k] = ew_[k];
  };
  if (2 * m >= live_count()) {
    halves_from(live_count(), min_parallel_copies, [&](std::size_t begin, std::size_t end, int) {
      live_range(begin, end, [&](std::uint32_t k) { slot_moved_[3 + k] = 0, set_slot(k); });
    });
  } else {
    live_range(0, live_count(), [&](std::uint32_t k) { slot_moved_[3 + k] = 0; });
    for (const RestContact& c : contacts_) {
      if (c.inv_a > 0.0) set_slot(c.a);
      if (c.b < n && c.inv_b > 0.0) set_slot(c.b);
    }
  }
}

// Inlined into build_rows()' loop, as push_row() into the sweeps'.
template <class Real>
[[gnu::always_inline]] inline void DiscContacts<Real>::fill_row(std::uint32_t i,
                                                                const RestContact& c,
                                                                std::uint32_t a, std::uint32_t b) {
  const bool pair = c.b < discs_.size();
  const double inv_a = c.inv_a, inv_b = pair ? c.inv_b : 0.0;
  // The effective masses as the gather made them: 1 / (1/m_a + 1/m_b), and along the tangent
  // with the rolling discs' turns.
  const double mass = 1.0 / (inv_a + inv_b);
  if (rolling_) {
    RollRow t = roll_row(c);
    t.mass_t = 1.0 / (pair ? inv_a + inv_b + t.arm_a * t.turn_a + t.arm_b * t.turn_b
                           : inv_a + t.arm_a * t.turn_a);
    roll_rows_[i] = t;
  }
  SolveRow& r = rows_[i];
  r.a = a, r.b = b;
  r.nx = c.nx, r.ny = c.ny, r.mass = mass, r.friction = c.friction;
  r.lambda_n = c.lambda_n, r.lambda_t = c.lambda_t;
  r.inv_a = inv_a, r.inv_b = inv_b;
  const double inv = inv_a + inv_b;
  push_rows_[i] = PushRow{.a = c.a,
                          .b = c.b,
                          .radii = c.radii,
                          .r_min = c.r_min,
                          .w_a = inv_a / inv,
                          .w_b = inv_b / inv};
}

template <class Real>
void DiscContacts<Real>::build_rows(const Tick& tick) {
  const std::size_t n = discs_.size(), m = contacts_.size();
  rows_.resize(m);
  push_rows_.resize(m);
  row_moved_.resize(m);
  roll_rows_.resize(rolling_ ? m : 0);
  row_kind_ = (rolling_ ? rolling_rows : 0) | (kinematic_contacts_ ? kinematic_rows : 0);
  sv_.resize(3 + n);
  sw_.resize(rolling_ ? 3 + n : 0);
  slot_moved_.resize(3 + n);
  for (std::size_t s = 0; s < 3; ++s) {  // parts 0, 1 and across the cut: a fixed velocity 0
    sv_[s] = SolveVelocity{}, slot_moved_[s] = 0;
    if (rolling_) sw_[s] = 0.0;
  }
  set_slots();
  // A moving kinematic partner's slot: its velocity for the tick (appended: one thread only).
  auto fixed = [&](double vx, double vy, double w) {
    sv_.push_back({vx, vy});
    if (rolling_) sw_.push_back(w);
    return std::uint32_t(sv_.size() - 1);
  };
  auto spin = [&](std::uint32_t k) { return rolling_ ? ew_[k] : 0.0; };
  const bool any_kinematic = kinematic_contacts_;
  const auto& p = part_start_;
  auto fill = [&](std::uint32_t begin, std::uint32_t end, int /*thread*/) {
    const std::uint32_t part = begin >= p[2] ? 2 : begin >= p[1] ? 1 : 0;
    // A moving disc's slot is its own (set_slots()), a still partner's its part's.
    auto slot = [&](std::uint32_t k, bool moves, bool kinematic) -> std::uint32_t {
      if (kinematic) return fixed(evx_[k], evy_[k], spin(k));
      return moves ? 3 + k : part;
    };
    with_row_kind([&](auto kind) {
      for (std::uint32_t i = begin; i < end; ++i) {
        const RestContact& c = contacts_[order_[i]];
        // Which partner is a moving kinematic one: asked only when some contact has one.
        const bool pair = c.b < n;
        const bool kinematic_a = any_kinematic && moving_kinematic(c.a);
        const bool kinematic_b = any_kinematic && pair && moving_kinematic(c.b);
        const std::uint32_t a = slot(c.a, c.inv_a > 0.0, kinematic_a);
        std::uint32_t b = part;  // a plane or a still segment
        if (pair) {
          b = slot(c.b, c.inv_b > 0.0, kinematic_b);
        } else if (const Vec2 u = any_kinematic ? wall_velocity(tick, c) : Vec2{};
                   u.x != 0.0 || u.y != 0.0) {
          b = fixed(u.x, u.y, 0.0);  // a moving segment
        }
        fill_row(i, c, a, b);
        const SolveRow& r = rows_[i];
        // The warm start: last tick's impulses on the slots, row by row in each part, while the
        // row is at hand (a pass of its own read every row again).
        row_moved_[i] = 0;
        if (r.lambda_n == 0.0 && r.lambda_t == 0.0) continue;
        row_moved_[i] = 1;
        push_row<kind()>(i, r, sv_[r.a], sv_[r.b], r.lambda_n, r.lambda_t);
        if constexpr ((kind() & rolling_rows) != 0) turn(i, r.lambda_t);
      }
    });
  };
  if (kinematic_contacts_) {  // rows that append slots: on this thread, part by part
    for (int part = 0; part < 3; ++part) fill(p[part], p[part + 1], 0);
    slot_moved_.resize(sv_.size(), 0);
  } else {
    parts_pass(fill);
  }
}

template <class Real>
void DiscContacts<Real>::scatter_rows(double kdt) {
  // Each row's impulses go where its contact is in contacts_ (order_ is a permutation of it),
  // in warm_: the next tick's warm start, in contacts_' two runs in key order.
  warm_.resize(contacts_.size());
  warm_pairs_ = plane_contacts_;
  auto rows = [&](std::uint32_t begin, std::uint32_t end, int /*thread*/) {
    // Pointers in registers: the bytes stored in slot_moved_ may alias anything in memory.
    const std::uint32_t* const order = order_.data();
    const SolveRow* const solved = rows_.data();
    const PushRow* const pushed = push_rows_.data();
    const std::uint8_t* const moved = row_moved_.data();
    std::uint8_t* const marks = slot_moved_.data();
    WarmImpulse* const warm = warm_.data();
    for (std::uint32_t i = begin; i < end; ++i) {
      const std::uint32_t j = order[i];
      const SolveRow& r = solved[i];
      // Every contact's key is a << 32 | b (pair_key, wall_contact): from the row's push-out
      // half, read in row order, rather than from the contact, read out of it.
      const std::uint64_t key = (std::uint64_t(pushed[i].a) << 32) | pushed[i].b;
      assert(key == contacts_[j].key());
      warm[j] = WarmImpulse{key, r.lambda_n, r.lambda_t};
      if (moved[i]) marks[r.a] = marks[r.b] = 1;
    }
  };
  parts_pass(rows);
  // Each moved disc once (its mark goes from 1 to 2), by disc: its slot started at evx_, evy_
  // (untouched since build_rows()).
  halves_from(live_count(), min_parallel_copies, [&](std::size_t begin, std::size_t end, int) {
    live_range(begin, end, [&](std::uint32_t k) {
      std::uint8_t& mark = slot_moved_[3 + k];
      if (mark != 1) return;
      const SolveVelocity& v = sv_[3 + k];
      if (!held_[k].on) {  // a held disc is where the contact stopped it already
        ex_[k] += kdt * (v.x - evx_[k]), ey_[k] += kdt * (v.y - evy_[k]);
      }
      evx_[k] = v.x, evy_[k] = v.y;
      if (rolling_) ew_[k] = sw_[3 + k];
      mark = 2;
    });
  });
}

}  // namespace fixstep::detail
