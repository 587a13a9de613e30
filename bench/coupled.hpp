// The coupled-systems benchmark (bench_coupled.cpp): its two scenes, the common state and
// energy, the peer engines behind one interface (peers_chipmunk.cpp, peers_box2d.cpp) and
// the reference solution (coupled_reference.cpp). Internal to bench/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace coupled {

// The chain: n bodies of m = 1 kg on the x axis, body 0 tied to an anchor at the origin by an
// anchored spring, body j to body j + 1 by a link, every spring k = 400 N/m and b = 2 N·s/m
// (rest length 0, damping proportional: b = 0.005 s · k), the last body pulled along +x by
// F = 40 N. Every spring then carries F in equilibrium, stretched by F/k = 0.1 m: body j rests
// at x = 0.1 (j + 1) m. It starts there with v_j = 0.5 sin(2π(j+1)/16) + 0.25 sin(2π(j+1)/4)
// m/s along x, so the motion stays on the x axis (where damping along a spring, as Chipmunk
// and Box2D damp, and damping of the whole relative velocity, as fixstep's L = 0 link damps,
// are the same force) and every link stays 0.07-0.13 m long (measured over 60 s): no link
// gets near zero length, where a spring's direction flips and Box2D's minimum length acts.
inline constexpr double chain_mass = 1.0;         // kg
inline constexpr double chain_stiffness = 400.0;  // N/m
inline constexpr double chain_damping = 2.0;      // N·s/m
inline constexpr double chain_pull = 40.0;        // N, on the last body along +x
// The cloth: side x side bodies of 1 kg on a 0.1 m grid, structural links (each body to its
// right and lower neighbour) k = 400 N/m, b = 2 N·s/m, every body on the border held by an
// anchored spring (k, b) whose anchor is placed so that the grid is the equilibrium (a frame
// holding the cloth stretched). It starts on the grid with a smooth velocity pattern.
inline constexpr double cloth_spacing = 0.1;  // m

enum class SceneKind { chain, cloth };
[[nodiscard]] const char* scene_name(SceneKind s);

struct Scene {
  SceneKind kind = SceneKind::chain;
  std::vector<fixstep::BodyDef> bodies{};   ///< mass, initial state, anchored spring, pull
  std::vector<fixstep::IndexLink> links{};  ///< rest length 0
  /// When not empty: the scene with every spring given a small rest length L behaves exactly
  /// like this one (rest length 0) shifted by L·rest_shift[j] per body, as long as no spring
  /// changes direction (true for the chain: all springs point along -x from b to a). Box2D
  /// clamps rest lengths to b2_linearSlop; its bodies start shifted and are read back
  /// unshifted, so its states are comparable with the exact solution. Empty for the cloth.
  std::vector<fixstep::Vec2> rest_shift{};
};

[[nodiscard]] Scene make_chain(std::size_t n);
[[nodiscard]] Scene make_cloth(std::size_t side);
[[nodiscard]] Scene make_scene(SceneKind kind, std::size_t bodies);  ///< cloth: side = √bodies

/// The scene's links as a WorldDef holds them (by the handles World(def) gives its bodies).
[[nodiscard]] inline std::vector<fixstep::LinkDef> link_defs(const Scene& s) {
  std::vector<fixstep::LinkDef> out;
  out.reserve(s.links.size());
  for (const fixstep::IndexLink& l : s.links) {
    out.push_back({fixstep::defined_entity(l.body_a), fixstep::defined_entity(l.body_b), l.spring});
  }
  return out;
}

/// A fixstep World holding the scene (bodies in scene order, then the links in order).
template <class Real>
std::unique_ptr<fixstep::detail::WorldKernel<Real>> make_world(const Scene& s,
                                                               const fixstep::WorldSettings& ws) {
  auto w = std::make_unique<fixstep::detail::WorldKernel<Real>>(ws);
  w->reserve(s.bodies.size());
  std::vector<fixstep::Entity> e;
  e.reserve(s.bodies.size());
  for (const fixstep::BodyDef& d : s.bodies) e.push_back(w->create_body(d));
  for (const fixstep::IndexLink& l : s.links) {
    w->create_link({.body_a = e[l.body_a], .body_b = e[l.body_b], .spring = l.spring});
  }
  return w;
}

/// Mechanical energy of the scene's rest-length-0 model at a state, J: ½m|v|², ½k|d|² per
/// spring, -F·x per pulled body (the World's potentials).
[[nodiscard]] double energy(const Scene& s, std::span<const fixstep::Body> state);
/// Energy of the static equilibrium, J: the chain's initial positions at rest; for the cloth,
/// its grid at rest. The energy the motion can lose is energy() minus this.
[[nodiscard]] double equilibrium_energy(const Scene& s);

/// A stepper (fixstep, the edge-list loop or a peer engine) stepping a scene at a fixed dt. state()
/// reports positions and velocities in the scene's coordinates (undoing rest_shift where the peer
/// needed it).
class Peer {
 public:
  virtual ~Peer() = default;
  virtual void step() = 0;
  virtual void state(std::span<fixstep::Body> out) const = 0;
  /// Energy its damping took out so far, J, when it keeps that account (fixstep with
  /// WorldSettings::track_dissipation); NaN otherwise.
  [[nodiscard]] virtual double dissipated() const;
  /// Threads the last step used.
  [[nodiscard]] virtual int threads_used() const { return 1; }
};

/// A stepper by key (see timed_steppers() and accurate_steppers()) on scene s at step dt;
/// track: fixstep keeps its dissipation account (WorldSettings::track_dissipation).
[[nodiscard]] std::unique_ptr<Peer> make_stepper(const std::string& key, const Scene& s, double dt,
                                                 bool track = false);

/// Chipmunk2D (cpSpace, cpDampedSpring; double precision). Iterations of its impulse solver.
inline constexpr int chipmunk_iterations = 10;
[[nodiscard]] std::unique_ptr<Peer> make_chipmunk(const Scene& s, double dt);
[[nodiscard]] std::string chipmunk_version();

/// Box2D (b2World, b2DistanceJoint; float). Velocity and position iterations per Step.
inline constexpr int box2d_velocity_iterations = 8;
inline constexpr int box2d_position_iterations = 3;
[[nodiscard]] std::unique_ptr<Peer> make_box2d(const Scene& s, double dt);
[[nodiscard]] std::string box2d_version();
/// The rest length Box2D 2.4 gives a distance joint asked for length 0 (b2_linearSlop), m.
[[nodiscard]] double box2d_min_length();

/// The reference solution of a scene with proportional damping (the chain) at the given
/// times, s: every body's state per time.
struct Reference {
  std::string method{};  ///< how it was computed, for the report
  std::vector<std::vector<fixstep::Body>> states{};
};
[[nodiscard]] Reference reference(const Scene& s, std::span<const double> times);
/// The same from fixstep's RK4 at h = 1/60 s / substeps (the independent cross-check).
[[nodiscard]] Reference rk4_reference(const Scene& s, std::span<const double> times, int substeps);

// --- results and the report (coupled_report.cpp) ------------------------------------------

/// The steppers timed, by key: fixstep_<f64|f32>_t<1|2> (World::step, semi-implicit Euler,
/// 1 or 2 threads), edge_<f64|f32> (the hand-written edge-list loop), chipmunk, box2d.
[[nodiscard]] std::span<const char* const> timed_steppers();
/// The steppers whose accuracy is measured: fixstep_f64, fixstep_f32 (each the same bits on
/// any thread count, and the same as its edge loop: checked), chipmunk, box2d.
[[nodiscard]] std::span<const char* const> accurate_steppers();
/// Human-readable name of a stepper key.
[[nodiscard]] std::string stepper_label(const std::string& key);
/// The timed stepper whose cost an accuracy stepper has (fixstep_f64 -> fixstep_f64_t1).
[[nodiscard]] std::string timing_key(const std::string& accuracy_key);

/// One stepper on the chain at one N and dt, over `duration`, against the reference.
struct Accuracy {
  std::string stepper{};
  std::size_t n = 0;
  double dt = 0.0;              ///< s
  double err_max = 0.0;         ///< m: largest |x - x_ref| over bodies and samples (every 1/30 s)
  double err_end = 0.0;         ///< m: largest |x - x_ref| over bodies at the end
  double energy_end = 0.0;      ///< (E(T) - E_eq) / (E(0) - E_eq): the motion's energy left
  double energy_ref_end = 0.0;  ///< the same for the reference
  double balance = 0.0;   ///< (E(T) + D(T) - E(0)) / (E(0) - E_eq), D = dissipated; NaN if no D
  double min_link = 0.0;  ///< m: shortest link seen at the samples
};

struct Timing {
  double ns_per_body_step = 0.0;  ///< median real time per step / bodies
  double bodies = 0.0;
};

struct Results {
  std::map<std::string, Timing> timings{};  ///< key "<scene>/<stepper>/<N asked for>"
  std::vector<Accuracy> accuracy{};
  std::vector<std::int64_t> sizes{};  ///< N asked for (the cloth takes side = round(√N))
  std::string reference_method{};
  double duration = 0.0;  ///< s, of the accuracy runs
  int repetitions = 1;
};

/// The markdown of docs/PERFORMANCE.md's coupled section: setup line, cost, speed-ups,
/// accuracy, energy and the targets (met / missed with the measured ratio).
[[nodiscard]] std::string report_markdown(const Results& r);
/// The work-precision plot (chain, N = 10³): error against cost per simulated second, as a
/// PNG at `path`; false (and nothing written) when the timings of N = 10³ are missing.
bool write_plot(const Results& r, const std::string& path);

}  // namespace coupled
