// Disc contacts, phase 2: the velocity iterations' and the push-out's own copies of what they
// read and write. The contacts in solving order (order_) become rows of the fields an impulse
// needs, and the discs they move get slots in one array of velocities, numbered as the rows
// first meet them: a sweep then reads and writes one compact array in nearly the order it lies
// in memory, and never a position (an impulse acts as a constant force over the tick, so a
// disc's position changes by κ dt times its velocity's change: scatter_rows() moves it once,
// after the sweeps). A static disc, a plane or a still segment is the velocity-0 slot of the
// row's part; a moving kinematic partner gets a slot of its own per row. No slot is written by
// both threads. The push-out's rows hold what it needs of a contact and nothing else, in the
// same order.
#include "disc_contacts.hpp"

namespace fixstep::detail {

template <class Real>
void DiscContacts<Real>::build_rows() {
  const std::size_t n = discs_.size(), m = contacts_.size();
  if (slot_of_.size() != n) {
    slot_of_.assign(n, no_slot);
  } else {  // the last rows' slots (scatter_rows() may not have run: a stop request)
    for (const std::uint32_t k : slot_disc_) {
      if (k != no_slot) slot_of_[k] = no_slot;
    }
  }
  rows_.resize(m);
  push_rows_.resize(m);
  row_moved_.assign(m, 0);
  sv_.assign(3, SolveVelocity{});  // parts 0, 1 and across the cut: a fixed velocity 0
  slot_disc_.assign(3, no_slot);
  sw_.assign(rolling_ ? 3 : 0, 0.0);
  roll_rows_.resize(rolling_ ? m : 0);
  row_kind_ = rolling_ ? rolling_rows : 0;
  auto fixed = [&](double vx, double vy, double w) {
    sv_.push_back({vx, vy});
    if (rolling_) sw_.push_back(w);
    slot_disc_.push_back(no_slot);
    return std::uint32_t(sv_.size() - 1);
  };
  auto spin = [&](std::uint32_t k) { return rolling_ ? ew_[k] : 0.0; };
  auto slot = [&](std::uint32_t k, bool moves, bool kinematic, std::uint32_t part) {
    if (kinematic) return fixed(evx_[k], evy_[k], spin(k));
    if (!moves) return part;
    if (slot_of_[k] == no_slot) {
      slot_of_[k] = std::uint32_t(sv_.size());
      sv_.push_back({evx_[k], evy_[k]});
      if (rolling_) sw_.push_back(ew_[k]);
      slot_disc_.push_back(k);
    }
    return slot_of_[k];
  };
  for (std::uint32_t part = 0; part < 3; ++part) {
    for (std::uint32_t i = part_start_[part]; i < part_start_[part + 1]; ++i) {
      const RestContact& c = contacts_[order_[i]];
      SolveRow& r = rows_[i];
      r.a = slot(c.a, c.inv_a > 0.0, c.kinematic_a, part);
      if (c.b < n) {
        r.b = slot(c.b, c.inv_b > 0.0, c.kinematic_b, part);
      } else {
        r.b = c.kinematic_b ? fixed(c.bvx, c.bvy, 0.0) : part;  // a moving segment, or still
      }
      if (c.kinematic_a || c.kinematic_b) row_kind_ |= kinematic_rows;
      if (rolling_) roll_rows_[i] = RollRow{c.arm_a, c.arm_b, c.turn_a, c.turn_b};
      r.nx = c.nx, r.ny = c.ny, r.mass = c.mass, r.mass_t = c.mass_t, r.friction = c.friction;
      r.lambda_n = c.lambda_n, r.lambda_t = c.lambda_t;
      r.inv_a = c.inv_a, r.inv_b = c.b < n ? c.inv_b : 0.0;
      const double inv = r.inv_a + r.inv_b;
      push_rows_[i] = PushRow{.a = c.a,
                              .b = c.b,
                              .radii = c.radii,
                              .r_min = c.r_min,
                              .w_a = r.inv_a / inv,
                              .w_b = r.inv_b / inv};
    }
  }
  sv0_ = sv_;
  slot_moved_.assign(sv_.size(), 0);
}

template <class Real>
void DiscContacts<Real>::scatter_rows(double kdt) {
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    RestContact& c = contacts_[order_[i]];
    const SolveRow& r = rows_[i];
    c.lambda_n = r.lambda_n, c.lambda_t = r.lambda_t;
    if (!row_moved_[i]) continue;
    c.moved = 1;
    slot_moved_[r.a] = slot_moved_[r.b] = 1;
  }
  for (std::size_t s = 3; s < sv_.size(); ++s) {
    const std::uint32_t k = slot_disc_[s];
    if (k == no_slot || !slot_moved_[s]) continue;
    evx_[k] = sv_[s].x, evy_[k] = sv_[s].y;
    if (rolling_) ew_[k] = sw_[s];
    ex_[k] += kdt * (sv_[s].x - sv0_[s].x), ey_[k] += kdt * (sv_[s].y - sv0_[s].y);
  }
}

#define FIXSTEP_INSTANTIATE(Real)                 \
  template void DiscContacts<Real>::build_rows(); \
  template void DiscContacts<Real>::scatter_rows(double);
FIXSTEP_INSTANTIATE(float)
FIXSTEP_INSTANTIATE(double)
#undef FIXSTEP_INSTANTIATE

}  // namespace fixstep::detail
