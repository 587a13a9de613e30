// Bodies with shapes (BodyDef::shapes), the kernel's side: their shapes, mass properties,
// angle and angular velocity, the shape world rebuilt after a structural change, and the tick's
// shape phase (shape_world.hpp has what it does). Included by kernel_instances.cpp.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "contact_kappa.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/shape.hpp"
#include "owner_ptrs.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace detail {
template class ClonePtr<ShapeWorld>;
}  // namespace detail

namespace {

/// The least distance from a shape's middle (its vertices' mean) to its surface, m: its
/// radius for a circle or capsule, the nearest face plus the rounding for a polygon (Box2D's
/// minExtent, b2ComputeShapeExtent).
double thinnest(const detail::Convex& c) {
  if (c.count <= 2) return c.radius;
  Vec2 mid{};
  for (int i = 0; i < c.count; ++i) mid = mid + c.vertices[i];
  mid = mid / c.count;
  double least = INFINITY;
  for (int i = 0; i < c.count; ++i) {
    least = std::min(least, dot(c.normals[i], c.vertices[i] - mid));
  }
  return least + c.radius;
}

}  // namespace

template <class Real>
void detail::WorldKernel<Real>::add_shapes(Entity e, const BodyDef& def, const std::string& who) {
  ShapeSet set;
  set.defs = def.shapes;
  set.angle = rounded_to<Real>(detail::wrap_angle(def.body.angle));
  set.spin = def.type == BodyType::static_body ? 0.0 : rounded_to<Real>(def.body.angular_velocity);
  const std::size_t j = bodies_.index(e);
  if (def.type == BodyType::dynamic) {
    const MassProperties mp = body_mass(def.shapes, def.body.mass);
    if (!(mp.mass > 0.0 && std::isfinite(mp.mass))) {
      throw std::invalid_argument(fmt::format("{}: its shapes give no mass", who));
    }
    set.center = mp.center;
    set.inertia = def.inertia ? *def.inertia : mp.inertia;
    mass_[j] = mp.mass;
  }
  const Vec2 c = def.body.position + rotate(rot_of(set.angle), set.center);
  x_[j] = prev_x_[j] = static_cast<Real>(c.x);
  y_[j] = prev_y_[j] = static_cast<Real>(c.y);
  shape_sets_.set.insert(e);
  shape_sets_.data.push_back(std::move(set));
}

template <class Real>
void detail::WorldKernel<Real>::check_shapes(const BodyDef& def, const std::string& who) const {
  if (def.shapes.empty()) return;
  if (def.collider) {
    throw std::invalid_argument(fmt::format("{}: has both a collider and shapes", who));
  }
  if (def.shapes.size() > max_shapes_per_body) {
    throw std::invalid_argument(
        fmt::format("{}: {} shapes, at most {}", who, def.shapes.size(), max_shapes_per_body));
  }
  for (std::size_t k = 0; k < def.shapes.size(); ++k) {
    if (auto problem = shape_problem(def.shapes[k])) {
      throw std::invalid_argument(fmt::format("{}: shapes[{}]: {}", who, k, *problem));
    }
  }
  if (def.inertia && !(*def.inertia >= 1e-100 && *def.inertia <= 1e100)) {
    throw std::invalid_argument(
        fmt::format("{}: inertia must be in [1e-100, 1e100] kg·m² (got {})", who, *def.inertia));
  }
  for (double v : {def.body.angle, def.body.angular_velocity}) {
    if (!(std::abs(v) <= max_state_magnitude)) {
      throw std::invalid_argument(
          fmt::format("{}: angle and angular_velocity must be finite, within 1e12", who));
    }
  }
}

// Angular input at the tick's start (world_input.cpp calls it for the angular kinds; entries
// of the wrong type or on a body without shapes are ignored, as World::check_input says).
template <class Real>
void detail::WorldKernel<Real>::apply_angular_input(const BodyInput& in, std::size_t j) {
  const Entity e = bodies_.dense[j];
  if (!shape_sets_.set.contains(e) || in.value.y != 0.0) return;
  ShapeSet& set = shape_sets_.data[shape_sets_.set.index(e)];
  const BodyType type = types_[j];
  const double v = in.value.x;
  if (type == BodyType::dynamic) {
    if (in.kind == BodyInputKind::torque) set.torque += v;
    if (in.kind == BodyInputKind::angular_impulse) {
      set.spin = rounded_to<Real>(set.spin + v / set.inertia);
    }
  } else if (type == BodyType::kinematic) {
    if (in.kind == BodyInputKind::angular_velocity) set.spin = rounded_to<Real>(v);
    if (in.kind == BodyInputKind::target_angle) {  // the shorter way round, over one tick
      const double turn = std::remainder(v - set.angle, 2.0 * std::numbers::pi);
      set.spin = rounded_to<Real>(turn / settings_.dt);
    }
  }
}

template <class Real>
void detail::WorldKernel<Real>::remove_shapes(Entity e) {
  if (!shape_sets_.set.contains(e)) return;
  const std::size_t i = shape_sets_.set.erase(e);
  if (i + 1 != shape_sets_.data.size()) shape_sets_.data[i] = std::move(shape_sets_.data.back());
  shape_sets_.data.pop_back();
}

template <class Real>
std::span<const ShapeDef> detail::WorldKernel<Real>::shapes(Entity e) const {
  require(e);
  if (!shape_sets_.set.contains(e)) return {};
  return shape_sets_.data[shape_sets_.set.index(e)].defs;
}

template <class Real>
Vec2 detail::WorldKernel<Real>::local_center(Entity e) const {
  require(e);
  if (!shape_sets_.set.contains(e)) return {};
  return shape_sets_.data[shape_sets_.set.index(e)].center;
}

template <class Real>
void detail::WorldKernel<Real>::rebuild_shapes() {
  if (shape_sets_.data.empty()) {
    shape_world_.reset();
    return;
  }
  if (!shape_world_) shape_world_.reset(new ShapeWorld());
  ShapeWorld& w = *shape_world_;
  w.reshape();
  w.bodies_.clear(), w.shapes_.clear();
  w.kept_.clear();  // keyed by the shapes' indices, which this may change
  const ContactSettings cs = settings_.contacts.value_or(ContactSettings{});
  auto add_shape = [&](const Convex& c, std::uint32_t owner, std::optional<double> mu,
                       std::optional<double> e, double rolling, const CollisionFilter& filter,
                       bool sensor, std::uint32_t key) {
    w.shapes_.push_back({c, owner, mu.value_or(cs.friction), e.value_or(cs.restitution), rolling,
                         filter, sensor, key});
  };
  for (std::size_t i = 0; i < shape_sets_.data.size(); ++i) {
    const Entity e = shape_sets_.set.dense[i];
    const ShapeSet& set = shape_sets_.data[i];
    const std::uint32_t j = static_cast<std::uint32_t>(bodies_.index(e));
    ShapedBody b;
    b.body = j, b.type = types_[j], b.set = static_cast<std::uint32_t>(i);
    if (b.type == BodyType::dynamic) b.inv_mass = 1.0 / mass_[j], b.inv_inertia = 1.0 / set.inertia;
    b.first = static_cast<std::uint32_t>(w.shapes_.size());
    b.count = static_cast<std::uint32_t>(set.defs.size());
    const auto owner = static_cast<std::uint32_t>(w.bodies_.size());
    for (std::size_t k = 0; k < set.defs.size(); ++k) {
      const ShapeDef& s = set.defs[k];
      const Convex c = to_convex(s, set.center);
      b.extent = std::max(b.extent, extent(c));
      b.thinnest = k == 0 ? thinnest(c) : std::min(b.thinnest, thinnest(c));
      add_shape(c, owner, s.friction, s.restitution, s.rolling_resistance, s.filter, s.sensor,
                static_cast<std::uint32_t>(e.slot() << 6 | k));
      if (s.one_way) {  // its frame's +y in the body's frame
        const Rot q = rot_of(s.angle);
        w.shapes_.back().one_way = true, w.shapes_.back().up = rotate(q, Vec2{0.0, 1.0});
      }
    }
    w.bodies_.push_back(b);
  }
  // Discs meet shapes here (and one another in the disc phase); a sensor disc sees them here.
  for (std::size_t i = 0; i < colliders_.data.size(); ++i) {
    const Collider& c = colliders_.data[i];
    if (!c.collide && !c.sensor) continue;
    const Entity e = colliders_.set.dense[i];
    const std::uint32_t j = static_cast<std::uint32_t>(bodies_.index(e));
    ShapedBody b;
    b.body = j, b.type = types_[j], b.disc = true, b.set = ShapedBody::none;
    if (b.type == BodyType::dynamic) b.inv_mass = 1.0 / mass_[j];
    b.first = static_cast<std::uint32_t>(w.shapes_.size()), b.count = 1;
    b.extent = b.thinnest = c.radius;
    Convex circle;
    circle.count = 1, circle.radius = c.radius;
    add_shape(circle, static_cast<std::uint32_t>(w.bodies_.size()), c.friction, c.restitution, 0.0,
              c.filter, c.sensor, static_cast<std::uint32_t>(e.slot() << 6));
    w.bodies_.push_back(b);
  }
  w.state_.assign(w.bodies_.size(), ShapeState{});
}

// The mechanical energy of each dynamic shaped body in the shape world's state (J): kinetic,
// translational and rotational, and the potential of its constant acceleration (gravity and
// ConstantForce, a = coefficient accel), −m a·x.
template <class Real>
void detail::WorldKernel<Real>::shape_energies(std::vector<double>& out) const {
  const ShapeWorld& w = *shape_world_;
  out.resize(w.bodies_.size());
  for (std::size_t i = 0; i < w.bodies_.size(); ++i) {
    const ShapedBody& b = w.bodies_[i];
    const ShapeState& s = w.state_[i];
    if (b.type != BodyType::dynamic) {
      out[i] = 0.0;
      continue;
    }
    const double m = mass_[b.body];
    const double ax = coeff_.accel_x.empty() ? 0.0 : double(coeff_.accel_x[b.body]);
    const double ay = coeff_.accel_y.empty() ? 0.0 : double(coeff_.accel_y[b.body]);
    const double turn = b.inv_inertia > 0.0 ? 0.5 * s.w * s.w / b.inv_inertia : 0.0;
    out[i] = 0.5 * m * (s.vx * s.vx + s.vy * s.vy) + turn - m * (ax * s.x + ay * s.y);
  }
}

// The energy account (WorldSettings::track_dissipation) of the tick's shape contacts: each
// dynamic body's loss of mechanical energy over the solve plus the work kinematic bodies did
// on it through their contact points (impulse · the kinematic point's velocity), per kg; the
// kinematic work is external.
template <class Real>
void detail::WorldKernel<Real>::account_shape_contacts() {
  ShapeWorld& w = *shape_world_;
  std::vector<double>& work = w.work_;
  work.assign(w.bodies_.size(), 0.0);
  for (const ShapeRow& r : w.rows()) {
    if (r.a == ShapeWorld::none) continue;
    const ShapedBody& a = w.bodies_[r.a];
    const ShapedBody& b = w.bodies_[r.b];
    const Vec2 p = (r.ln + r.bn) * r.n + (r.lt + r.bt) * Vec2{-r.n.y, r.n.x};  // on B; −p on A
    auto point_velocity = [&](std::uint32_t i, Vec2 arm) {
      const ShapeState& s = w.state_[i];
      return Vec2{s.vx - s.w * arm.y, s.vy + s.w * arm.x};
    };
    // (a rolling resistance's angular impulse lr on B, −lr on A, works against the other's ω)
    if (a.type == BodyType::kinematic && b.type == BodyType::dynamic) {
      work[r.b] += dot(p, point_velocity(r.a, r.ra)) + r.lr * w.state_[r.a].w;
    } else if (b.type == BodyType::kinematic && a.type == BodyType::dynamic) {
      work[r.a] -= dot(p, point_velocity(r.b, r.rb)) + r.lr * w.state_[r.b].w;
    }
  }
  for_shape_joints([&](const JointRecord& j, std::size_t) {  // motors' and kinematic ends' work
    if (j.a != JointRecord::none) work[j.a] += j.work_a;
    if (j.b != JointRecord::none) work[j.b] += j.work_b;
  });
  shape_energies(w.energy_after_);
  // A body the solve touched is measured against the tick's start (less what damping took in
  // the free step), as a resting disc is (disc_rest.cpp): holding a body at rest undoes the
  // free step's own energy error every tick (a semi-implicit Euler step from rest under
  // gravity loses ½ m g² dt²), which would otherwise pile up in the account of a body at rest;
  // one it did not touch lost nothing.
  w.touched_.assign(w.bodies_.size(), 0);
  for (const ShapeRow& r : w.rows()) {
    if (r.a != ShapeWorld::none) w.touched_[r.a] = 1;
    w.touched_[r.b] = 1;
  }
  for_shape_joints([&](const JointRecord& j, std::size_t) {
    if (j.a != JointRecord::none) w.touched_[j.a] = 1;
    if (j.b != JointRecord::none) w.touched_[j.b] = 1;
  });
  for (std::size_t i = 0; i < w.bodies_.size(); ++i) {
    const ShapedBody& b = w.bodies_[i];
    if (b.type != BodyType::dynamic) continue;
    const double damped =
        mass_[b.body] * (double(dissipated_body_[b.body]) - w.dissipated_start_[i]);
    const double before = w.touched_[i] ? w.energy_start_[i] - damped : w.energy_[i];
    const double lost = before - w.energy_after_[i] + work[i];
    dissipated_body_[b.body] += static_cast<Real>(lost / mass_[b.body]);
    external_work_ += work[i];
  }
}

template <class Real>
void detail::WorldKernel<Real>::unsettle_shapes() {
  if (shape_world_) shape_world_->unsettle();
}

template <class Real>
template <class F>
void detail::WorldKernel<Real>::for_shape_bodies(F&& f) {
  ShapeWorld& w = *shape_world_;
  if (!w.rest_stale()) {
    for (const std::uint32_t i : w.live()) f(i);
  } else if (!w.rest_whole()) {  // only bodies that fell asleep, woke or were moved changed
    for (const std::uint32_t i : w.visit_few()) f(i);
  } else {
    for (std::uint32_t i = 0; i < w.bodies_.size(); ++i) f(i);
  }
}

template <class Real>
template <class F>
void detail::WorldKernel<Real>::for_shape_joints(F&& f) {
  const ShapeWorld& w = *shape_world_;
  auto each = [&](std::size_t i) {
    if (!joint_records_[i].broken) f(joint_records_[i], i);
  };
  if (!w.rest_stale()) {
    for (const std::uint32_t i : w.live_joints()) each(i);
    return;
  }
  for (std::size_t i = 0; i < joint_records_.size(); ++i) each(i);
}

// A resting body's start is its state already (shape_rest.hpp): it has not moved since.
template <class Real>
void detail::WorldKernel<Real>::save_shape_start() {
  ShapeWorld& w = *shape_world_;
  for_shape_bodies([&](std::uint32_t i) {
    const ShapedBody& b = w.bodies_[i];
    ShapeState& s = w.state_[i];
    s.x0 = double(x_[b.body]), s.y0 = double(y_[b.body]);
    s.a0 = b.set == ShapedBody::none ? 0.0 : shape_sets_.data[b.set].angle;
  });
  if (!settings_.track_dissipation) return;
  // The account's start (account_shape_contacts): each dynamic body's energy before the free
  // step, and its damping account.
  w.energy_start_.resize(w.bodies_.size()), w.dissipated_start_.resize(w.bodies_.size());
  for (std::size_t i = 0; i < w.bodies_.size(); ++i) {
    const ShapedBody& b = w.bodies_[i];
    const std::uint32_t j = b.body;
    if (b.type != BodyType::dynamic) continue;
    const double m = mass_[j], vx = double(vx_[j]), vy = double(vy_[j]);
    const double ax = coeff_.accel_x.empty() ? 0.0 : double(coeff_.accel_x[j]);
    const double ay = coeff_.accel_y.empty() ? 0.0 : double(coeff_.accel_y[j]);
    const double spin = b.set == ShapedBody::none ? 0.0 : shape_sets_.data[b.set].spin;
    const double turn = b.inv_inertia > 0.0 ? 0.5 * spin * spin / b.inv_inertia : 0.0;
    w.energy_start_[i] =
        0.5 * m * (vx * vx + vy * vy) + turn - m * (ax * double(x_[j]) + ay * double(y_[j]));
    w.dissipated_start_[i] = double(dissipated_body_[j]);
  }
}

// An automatic world in which a pass of the phase could split (a colour of as many manifolds
// needs as many shapes) times the phase on two threads and on one now and then, and keeps the
// faster (thread_choice.hpp).
template <class Real>
int detail::WorldKernel<Real>::shape_phase_threads() {
  const bool choose =
      settings_.threads == 0 && (shape_world_->shapes_.size() >= ShapeWorld::min_split_manifolds ||
                                 joint_records_.size() >= ShapeWorld::min_split_joints);
  return shape_threads_.threads(detail::threads_for(settings_.threads), choose);
}

template <class Real>
void detail::WorldKernel<Real>::resolve_shapes() {
  ShapeWorld& w = *shape_world_;
  const double dt = settings_.dt;
  const double kappa = contact_kappa(settings_.integrator, settings_.substeps);
  // Sleepers solved as static, their flags set where they changed (the lists are then stale).
  if (sleep_ && w.rest_stale()) mark_shape_sleepers();
  for_shape_bodies([&](std::uint32_t i) {
    const ShapedBody& b = w.bodies_[i];
    ShapeState& s = w.state_[i];
    const std::uint32_t j = b.body;
    s.x = double(x_[j]), s.y = double(y_[j]), s.vx = double(vx_[j]), s.vy = double(vy_[j]);
    s.w = 0.0, s.a = s.a0;
    if (b.set == ShapedBody::none) return;
    ShapeSet& set = shape_sets_.data[b.set];
    // A torque input τ is a constant angular acceleration α = τ/I over the tick, stepped as
    // the integrator steps a constant acceleration: ω1 = ω0 + α dt, θ1 = θ0 + dt ω0 + κ dt² α
    // (κ as for a contact impulse: 1 for semi-implicit Euler, ½ for the methods exact for a
    // constant force). Without one, θ1 = θ0 + dt ω0.
    const double alpha = set.torque != 0.0 ? set.torque / set.inertia : 0.0;
    s.w = set.spin + alpha * dt;
    s.a = s.a0 + dt * set.spin + kappa * dt * dt * alpha;
    set.torque = 0.0;
  });
  const ContactSettings cs = settings_.contacts.value_or(ContactSettings{});
  ShapeTick tick;
  tick.dt = dt;
  tick.kappa = kappa;
  tick.velocity_iterations = cs.velocity_iterations;
  tick.restitution_threshold = cs.restitution_threshold;
  tick.position_iterations = cs.position_iterations;
  tick.planes = planes_;
  tick.segments = segments_.defs();
  tick.segment_grid = &segments_;
  tick.joints = joint_records_;
  tick.unpaired = joint_unpaired_, tick.unpaired_start = joint_unpaired_start_;
  tick.pre_solve = pre_solve_, tick.pre_solve_context = pre_solve_context_;
  tick.entities = bodies_.dense;
  tick.threads = shape_phase_threads();
  // The discs' second thread where its run is open (it spins through the shape phase); else
  // the shape world starts its own.
  detail::SecondThread* discs = discs_ && tick.threads >= 2 ? discs_->second_thread(2) : nullptr;
  tick.thread = discs != nullptr && discs->is_open() ? discs : nullptr;
  if (sleep_) {  // one paired with a mover wakes its island
    tick.wake = &WorldKernel::wake_shape_sleepers, tick.wake_context = this;
  }
  const bool account = settings_.track_dissipation;
  if (account) shape_energies(w.energy_);
  const ShapeTally tally = shape_threads_.timed([&] { return w.solve(tick); });
  if (account) account_shape_contacts();
  if (!joint_records_.empty()) break_joints();  // world_joints.cpp
  if (tally.cap && !fault_) {  // cold: a work limit stopped the tick's shape contacts
    const std::uint32_t j = w.bodies_[tally.cap_body].body;
    record_cap_fault(j, tally.cap, tally.limit,
                     fmt::format("{} shapes (the widest box is this body's; the broadphase "
                                 "pairs their boxes at the tick's start, grown by each body's "
                                 "motion over the tick)",
                                 w.shapes_.size()));
  }
  contact_stats_.shape_points = tally.points;
  contact_stats_.deepest_shape_overlap = tally.deepest;
  contact_stats_.shape_velocity_sweeps = tally.velocity_sweeps;
  // The live bodies' state back (a resting body's is unchanged: shape_rest.hpp).
  bool out_of_range = false;
  for (const std::uint32_t i : w.live()) {
    const ShapedBody& b = w.bodies_[i];
    const ShapeState& s = w.state_[i];
    if (b.set != ShapedBody::none) {
      ShapeSet& set = shape_sets_.data[b.set];
      set.angle = rounded_to<Real>(detail::wrap_angle(s.a));
      set.spin = rounded_to<Real>(s.w);
      out_of_range = out_of_range || !(std::abs(set.spin) <= max_state_magnitude);
    }
    if (b.type != BodyType::dynamic) continue;
    const std::uint32_t j = b.body;
    x_[j] = static_cast<Real>(s.x), y_[j] = static_cast<Real>(s.y);
    vx_[j] = static_cast<Real>(s.vx), vy_[j] = static_cast<Real>(s.vy);
    for (const double v : {s.x, s.y, s.vx, s.vy}) {
      out_of_range = out_of_range || !(std::abs(v) <= max_state_magnitude);
    }
  }
  if (out_of_range && !fault_) record_fault();
}

}  // namespace fixstep
