// The network stability guard (stability.hpp): bodies joined by links are judged by the
// network's fastest mode and its damping mode, not body by body.
//
// Power iteration. For the symmetric positive semidefinite A = M^-½ K M^-½ (or M^-½ C M^-½)
// the Rayleigh quotient ρ_t = x_tᵀ A x_t of x_t = A^t x_0 / |A^t x_0| never decreases and
// tends to λ_max (Golub & Van Loan, Matrix Computations, 4th ed., §8.2.1). Its error falls
// like (λ_2/λ_max)^{2t} when the top eigenvalue stands alone, but the top of a long chain's
// spectrum is a dense band: the weights (λ/λ_max)^{2t} then average over the eigenvalues within
// about λ_max/t of the edge and the error falls only like c/t (c = 1/4 for a uniform chain,
// 1/2 for a uniform 2-D grid; independent of n), and for a chain of some hundred bodies,
// where only a handful of eigenvalues lie that close, in between the two. For an error c/t,
// ρ_t - ρ_{t/2} = c/t is the error itself; when the error falls faster (a lone or resolved
// top eigenvalue) it overestimates it. Iteration stops when that estimate is below 1e-3 of ρ
// (after at least 20 iterations, at most 10000): about 250 iterations on a uniform chain of
// any length. The estimate is not a bound: a start vector with little weight on the top
// eigenvectors leaves more. In a model of this iteration (the chain's exact eigenvalues, 40
// random start vectors per length, 30 to 1000 bodies) the error at the stop was at most 3
// times the estimate: λ_max within 3e-3, ω_max (its square root) within 1.5e-3. The start
// vector here is fixed pseudo-random, so the result is deterministic.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/work_progress.hpp"
#include "fixstep/core/world_settings.hpp"
#include "stability_internal.hpp"
#include "stability_verdict.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

using detail::stability_tolerance;
constexpr double unbounded = std::numeric_limits<double>::infinity();

/// A symmetric 2×2 block [xx xy; xy yy] (N/m or N·s/m).
struct Sym2 {
  double xx = 0.0, xy = 0.0, yy = 0.0;
};

/// Unit direction of d and its length (0 and a zero direction for d = 0).
std::pair<Vec2, double> direction(Vec2 d) {
  const double len = det::hypot(d.x, d.y);
  return {len > 0.0 ? Vec2{d.x / len, d.y / len} : Vec2{}, len};
}

/// Tangent stiffness k [(1 - L/ℓ) I + (L/ℓ) d̂d̂ᵀ] of a spring at separation d, with the
/// transverse part 1 - L/ℓ clamped at 0 and k I where ℓ = 0 or L = 0.
Sym2 stiffness_block(double k, double rest, Vec2 d) {
  const auto [n, len] = direction(d);
  if (rest == 0.0 || len == 0.0) return {k, 0.0, k};
  const double t = std::max(0.0, 1.0 - rest / len);
  return {k * (t + (1.0 - t) * n.x * n.x), k * (1.0 - t) * n.x * n.y,
          k * (t + (1.0 - t) * n.y * n.y)};
}

/// A link damper: b I with L = 0 (or no direction), b d̂d̂ᵀ along the spring otherwise.
Sym2 link_damping_block(double b, double rest, Vec2 d) {
  const auto [n, len] = direction(d);
  if (rest == 0.0 || len == 0.0) return {b, 0.0, b};
  return {b * n.x * n.x, b * n.x * n.y, b * n.y * n.y};
}

/// M^-½ A M^-½ on the 2n-vector (x0, y0, x1, y1, ...), A assembled from a block per body (on
/// the diagonal) and per link (in the pattern [S -S; -S S] of its ends).
struct Operator {
  std::span<const fixstep::IndexLink> links;
  std::vector<double> scale;  // 1/sqrt(m), kg^-½
  std::vector<Sym2> body, link;

  void apply(const std::vector<double>& in, std::vector<double>& out,
             std::vector<double>& z) const {
    const std::size_t n = scale.size();
    for (std::size_t i = 0; i < 2 * n; ++i) z[i] = scale[i / 2] * in[i];
    for (std::size_t i = 0; i < n; ++i) {
      const Sym2& s = body[i];
      out[2 * i] = s.xx * z[2 * i] + s.xy * z[2 * i + 1];
      out[2 * i + 1] = s.xy * z[2 * i] + s.yy * z[2 * i + 1];
    }
    for (std::size_t l = 0; l < links.size(); ++l) {
      const std::size_t a = 2 * links[l].body_a, b = 2 * links[l].body_b;
      const double rx = z[a] - z[b], ry = z[a + 1] - z[b + 1];
      const Sym2& s = link[l];
      const double fx = s.xx * rx + s.xy * ry, fy = s.xy * rx + s.yy * ry;
      out[a] += fx, out[a + 1] += fy, out[b] -= fx, out[b + 1] -= fy;
    }
    for (std::size_t i = 0; i < 2 * n; ++i) out[i] *= scale[i / 2];
  }
};

double inner(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

struct Eigenpair {
  double value = 0.0;          // Rayleigh quotient, the estimate of λ_max
  std::vector<double> vector;  // unit vector
  int iterations = 0;
  double error = 0.0;  // estimated relative shortfall of value (see the file comment)
};

/// Power iteration with the Rayleigh quotient (see the file comment).
Eigenpair top_eigenpair(const Operator& op) {
  constexpr int min_iterations = 20, max_iterations = 10000;
  constexpr double tolerance = 1e-3;
  const std::size_t dim = 2 * op.scale.size();
  Eigenpair e;
  e.vector.resize(dim);
  if (dim == 0) return e;
  std::uint64_t state = 0x853c49e6748fea9bULL;
  for (double& v : e.vector) {  // splitmix64, uniform in [-1, 1)
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    v = static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-52 - 1.0;
  }
  const double norm0 = std::sqrt(inner(e.vector, e.vector));
  for (double& v : e.vector) v /= norm0;
  std::vector<double> y(dim), z(dim), history{0.0};  // history[t] = ρ_t
  for (int t = 1; t <= max_iterations; ++t) {
    throw_if_stop_requested();  // one operator product per iteration (stop_request.hpp)
    op.apply(e.vector, y, z);
    report_work_progress("stability guard", "iteration", static_cast<std::uint64_t>(t),
                         max_iterations);
    const double rho = inner(e.vector, y), norm = std::sqrt(inner(y, y));
    e.value = rho, e.iterations = t;
    history.push_back(rho);
    if (!(norm > 0.0) || !std::isfinite(norm)) return e;  // A x = 0, or overflow
    for (std::size_t i = 0; i < dim; ++i) e.vector[i] = y[i] / norm;
    e.error = std::max(0.0, rho - history[static_cast<std::size_t>(t / 2)]) / rho;
    if (t >= min_iterations && e.error <= tolerance) return e;
  }
  return e;
}

bool strang(Integrator i) {
  return i == Integrator::velocity_verlet || i == Integrator::forest_ruth;
}

/// λ_max(M⁻¹C)·h up to which velocity Verlet and Forest–Ruth keep a damped network bounded
/// with its links' flows swept by colours (link_damping.hpp). Each flow is exact and
/// contracts, but sweeps and drifts alternate, and a network is not the two-body pair
/// network_amplification measures (which is exact at every h): measured on anchored uniform
/// chains of 10 and 100 bodies (k = 1 N/m, b = 5 N·s/m) and a chain with a stiff dashpot at
/// its end (tests/core/test_stability_network.cpp), they diverge from λh ≈ 5.5 (Verlet) and
/// λh ≈ 1.94 (Forest–Ruth, whose middle stage runs the flows backwards); these bounds sit
/// below both.
double swept_damping_bound(Integrator integrator) {
  return integrator == Integrator::velocity_verlet ? 5.0 : 1.8;
}

/// Largest stable step for the mode (ω, γ) as the network steps it (max_stable_step, with
/// network_amplification for the links' damping flows).
double mode_max_step(Integrator integrator, double omega, double gamma, bool damped_links) {
  if (!(damped_links && gamma > 0.0 && strang(integrator))) {
    return max_stable_step(integrator, omega, gamma);
  }
  if (omega == 0.0) return swept_damping_bound(integrator) / gamma;  // the damping mode
  const double rate = omega > 0.0 ? omega : gamma;
  return detail::largest_stable_step(rate, [&](double s) {
    return network_amplification(integrator, omega, gamma, s / rate, true) <=
           1.0 + stability_tolerance;
  });
}

/// The body with the largest displacement |M^-½ v| in the unit vector v.
std::size_t largest_body(const Operator& op, const std::vector<double>& v) {
  std::size_t best = 0;
  double size = -1.0;
  for (std::size_t i = 0; i < op.scale.size(); ++i) {
    const double s = op.scale[i] * det::hypot(v[2 * i], v[2 * i + 1]);
    if (s > size) size = s, best = i;
  }
  return best;
}

/// "network of 3 bodies and 2 springs": what the network's messages are about.
std::string network_subject(std::size_t bodies, std::size_t links) {
  return fmt::format("network of {} bod{} and {} spring{}", bodies, bodies == 1 ? "y" : "ies",
                     links, links == 1 ? "" : "s");
}

/// dt and substeps as the network guard takes them, or std::invalid_argument.
void check_step(double dt, int substeps) {
  if (!(std::isfinite(dt) && dt > 0.0)) {
    throw std::invalid_argument(
        fmt::format("network stability: dt must be finite and > 0 (got {})", dt));
  }
  if (substeps < 1) {
    throw std::invalid_argument(
        fmt::format("network stability: substeps must be >= 1 (got {})", substeps));
  }
}

/// A network's stiffness and damping operators and what the guard reads off its parts.
struct Assembly {
  explicit Assembly(std::span<const fixstep::IndexLink> links)
      : k_op{links, {}, {}, {}}, c_op{links, {}, {}, {}} {}
  Operator k_op, c_op;
  bool damped_links = false;  ///< some link that moves a body has b > 0
  bool damped = false;        ///< some body or such link has damping
  // Each spring's and damper's coefficient per mass of its lighter end (1/s², 1/s): the
  // entries of M^-½ K M^-½ and M^-½ C M^-½ are below them, and their sums bound λ_max.
  std::vector<double> per_mass;
  std::optional<std::size_t> stiffest_link, strongest_damper;  ///< NetworkStability's
};

/// The bodies' diagonal blocks of K and C and their 1/sqrt(m); throws for a dynamic body's
/// mass not finite and > 0.
void add_bodies(std::span<const BodyDef> bodies, Assembly& as) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyDef& d = bodies[i];
    if (d.type != BodyType::dynamic) {  // an immovable anchor: 1/m = 0, nothing of its own
      as.k_op.scale.push_back(0.0);
      as.k_op.body.emplace_back();
      as.c_op.body.emplace_back();
      continue;
    }
    if (!(std::isfinite(d.body.mass) && d.body.mass > 0.0)) {
      throw std::invalid_argument(
          fmt::format("network stability: body[{}] '{}': mass must be finite and > 0 (got {})", i,
                      d.name, d.body.mass));
    }
    as.k_op.scale.push_back(1.0 / std::sqrt(d.body.mass));
    const double bc = (d.spring ? d.spring->damping : 0.0) + (d.drag ? d.drag->coefficient : 0.0);
    as.k_op.body.push_back(d.spring ? stiffness_block(d.spring->stiffness, d.spring->rest_length,
                                                      {d.body.position.x - d.spring->anchor.x,
                                                       d.body.position.y - d.spring->anchor.y})
                                    : Sym2{});
    as.c_op.body.push_back({bc, 0.0, bc});
    as.damped = as.damped || bc > 0.0;
    as.per_mass.push_back((d.spring ? d.spring->stiffness : 0.0) / d.body.mass);
    as.per_mass.push_back(bc / d.body.mass);
  }
  as.c_op.scale = as.k_op.scale;
}

/// The links' blocks of K and C, the stiffest link and the strongest damper; throws for a
/// link end not among the bodies or both ends on one body.
void add_links(std::span<const BodyDef> bodies, std::span<const fixstep::IndexLink> links,
               Assembly& as) {
  const std::size_t n = bodies.size();
  double stiffest = 0.0, strongest = 0.0;
  for (std::size_t l = 0; l < links.size(); ++l) {
    const fixstep::IndexLink& link = links[l];
    if (link.body_a >= n || link.body_b >= n || link.body_a == link.body_b) {
      throw std::invalid_argument(
          fmt::format("network stability: spring[{}] joins bodies {} and {} of {}", l, link.body_a,
                      link.body_b, n));
    }
    const Body &a = bodies[link.body_a].body, &b = bodies[link.body_b].body;
    const Vec2 d{a.position.x - b.position.x, a.position.y - b.position.y};
    const LinkSpring& s = link.spring;
    as.k_op.link.push_back(stiffness_block(s.stiffness, s.rest_length, d));
    as.c_op.link.push_back(link_damping_block(s.damping, s.rest_length, d));
    // The masses that move: a static or kinematic end is an anchor (infinite mass), so the
    // link acts on the other end's mass alone; between two anchors it moves nothing.
    const bool move_a = bodies[link.body_a].type == BodyType::dynamic,
               move_b = bodies[link.body_b].type == BodyType::dynamic;
    if (!move_a && !move_b) continue;
    as.damped_links = as.damped_links || s.damping > 0.0;
    const double lighter = !move_a ? b.mass : !move_b ? a.mass : std::min(a.mass, b.mass);
    as.per_mass.push_back(s.stiffness / lighter);
    as.per_mass.push_back(s.damping / lighter);
    const double mu = move_a && move_b ? reduced_mass(a.mass, b.mass) : lighter;
    if (s.stiffness > 0.0 && s.stiffness / mu > stiffest)
      stiffest = s.stiffness / mu, as.stiffest_link = l;
    if (s.damping > 0.0 && s.damping / mu > strongest)
      strongest = s.damping / mu, as.strongest_damper = l;
  }
  as.damped = as.damped || as.damped_links;
}

/// The network's top stiffness mode and, when damped, its top damping mode: power iteration
/// on both operators (none when a coefficient per mass is beyond ~1e300, where the iteration
/// itself would overflow, and inf - inf trap in Debug).
struct Spectrum {
  bool huge = false;
  Eigenpair top, damp;
  double gamma_raw = 0.0;  ///< the top mode's Rayleigh quotient of M^-½ C M^-½, 1/s
};

/// Spectrum of the assembly, with omega_max, omega_error, iterations, gamma, damping_rate and
/// fastest_body (for the top mode) set in r.
Spectrum find_spectrum(const Assembly& as, NetworkStability& r) {
  Spectrum sp;
  sp.huge = std::any_of(as.per_mass.begin(), as.per_mass.end(),
                        [](double v) { return !(v <= 1e300 / 4.0); });
  if (!sp.huge) sp.top = top_eigenpair(as.k_op);
  // (std::max passes NaN on as 0: the overflow test looks at the raw values.)
  r.omega_max = std::sqrt(std::max(0.0, sp.top.value));
  r.omega_error = sp.top.error < 1.0 ? 1.0 / std::sqrt(1.0 - sp.top.error) - 1.0 : unbounded;
  r.iterations = sp.top.iterations;
  if (!sp.huge) r.fastest_body = fixstep::defined_entity(largest_body(as.k_op, sp.top.vector));
  if (as.damped && !sp.huge) {
    const std::size_t dim = sp.top.vector.size();
    std::vector<double> y(dim), z(dim);
    as.c_op.apply(sp.top.vector, y, z);
    sp.gamma_raw = inner(sp.top.vector, y);
    r.gamma = std::max(0.0, sp.gamma_raw);
    sp.damp = top_eigenpair(as.c_op);
    r.damping_rate = std::max(0.0, sp.damp.value);
  }
  return sp;
}

/// Whether some rate of the spectrum overflowed a double.
bool overflowed(const Spectrum& sp, const NetworkStability& r) {
  return sp.huge || !std::isfinite(sp.top.value) || !std::isfinite(r.omega_max * r.omega_max) ||
         !std::isfinite(sp.gamma_raw) || !std::isfinite(sp.damp.value);
}

/// The two test modes of a network as World steps it: the fastest (ω_max, γ) and the most
/// damped (0, λ_max(M⁻¹C)), those whose rate is not zero.
struct TestModes {
  struct Mode {
    double omega, gamma, max_step, radius;
  };
  Integrator integrator;
  bool damped_links;
  std::vector<Mode> modes;

  /// Spectral radius of one step h (s) on mode m. Beyond the swept damping bound the growth
  /// is a network's, not the pair's: reported as unbounded rather than the pair's contraction.
  [[nodiscard]] double radius_at(const Mode& m, double h) const {
    if (m.omega == 0.0 && damped_links && strang(integrator) &&
        h * m.gamma > swept_damping_bound(integrator)) {
      return unbounded;
    }
    return network_amplification(integrator, m.omega, m.gamma, h, damped_links);
  }
  /// Some mode grows at step h (s).
  [[nodiscard]] bool unstable(double h) const {
    return std::any_of(modes.begin(), modes.end(),
                       [&](const Mode& m) { return radius_at(m, h) > 1.0 + stability_tolerance; });
  }
  /// Each mode's largest stable step and radius at h (s); the smallest step and largest
  /// radius of them all into r.
  void measure(double h, NetworkStability& r) {
    for (Mode& m : modes) {
      m.max_step = mode_max_step(integrator, m.omega, m.gamma, damped_links);
      m.radius = radius_at(m, h);
      r.max_step = std::min(r.max_step, m.max_step);
      r.radius = std::max(r.radius, m.radius);
    }
  }
  /// The mode the message names: an unstable one before a stable one, then the lower bound.
  [[nodiscard]] const Mode& binding() const {
    auto grows = [](const Mode& m) { return m.radius > 1.0 + stability_tolerance; };
    std::size_t bind = 0;
    for (std::size_t i = 1; i < modes.size(); ++i) {
      const bool gi = grows(modes[i]), gb = grows(modes[bind]);
      if (gi != gb ? gi : modes[i].max_step < modes[bind].max_step) bind = i;
    }
    return modes[bind];
  }
};

/// "stiffest link 'a'–'b', k = 100 N/m, fastest body 'c'" (with the damping mode binding:
/// "strongest damper: link ..., b = ... N·s/m, ..."), as the network's message names them.
std::string name_culprits(std::span<const BodyDef> bodies,
                          std::span<const fixstep::IndexLink> links, const NetworkStability& r) {
  std::string naming;
  const std::optional<std::size_t> link = r.damping_bound ? r.strongest_damper : r.stiffest_link;
  if (link) {
    const fixstep::IndexLink& l = links[*link];
    naming = fmt::format(
        "{} link '{}'–'{}', {} = {:g} {}, ", r.damping_bound ? "strongest damper:" : "stiffest",
        bodies[l.body_a].name, bodies[l.body_b].name, r.damping_bound ? "b" : "k",
        r.damping_bound ? l.spring.damping : l.spring.stiffness, r.damping_bound ? "N·s/m" : "N/m");
  }
  return naming + fmt::format("fastest body '{}'", bodies[r.fastest_body.slot()].name);
}

/// The verdict on a network whose mode b binds, with its message (stability_verdict.hpp).
void judge_network(std::span<const BodyDef> bodies, std::span<const fixstep::IndexLink> links,
                   Integrator integrator, double dt, int substeps, const TestModes& tm,
                   const TestModes::Mode& b, NetworkStability& r) {
  const bool swept = r.damping_bound && tm.damped_links && strang(integrator);
  detail::GuardFinding f =
      detail::finding_of(network_subject(bodies.size(), links.size()), integrator, dt, substeps, r);
  f.step_name = r.damping_bound ? "λ_max(M⁻¹C)·h" : "ω_max·h";
  f.rate = r.damping_bound ? b.gamma : b.omega;
  f.named_max_step = b.max_step;
  f.bound_name = swept ? "bound of its swept link damping" : "stability bound";
  f.rates = {{{"ω_max", r.omega_max, "rad/s"},
              {"γ", r.gamma, "1/s"},
              {"λ_max(M⁻¹C)", r.damping_rate, "1/s"}}};
  f.naming = name_culprits(bodies, links, r);
  f.infinite_diverges = true;
  detail::Judgement j = detail::judge(f, [&](double h) { return tm.unstable(h); });
  r.verdict = j.verdict, r.min_substeps = j.min_substeps, r.message = std::move(j.message);
}

}  // namespace

double network_amplification(Integrator integrator, double omega, double gamma, double h,
                             bool damped_links) {
  if (!(damped_links && gamma > 0.0 && strang(integrator))) {
    return amplification(integrator, omega, gamma, h);
  }
  if (const double c = detail::unit_scale(omega, gamma); c != 1.0) {  // within a world's ranges
    return network_amplification(integrator, omega / c, gamma / c, h * c, damped_links);
  }
  detail::WorldKernel<double> w(WorldSettings{
      .dt = h, .integrator = integrator, .substeps = 1, .flush_denormals = false, .threads = 1});
  // Two pairs of unit masses; each pair's separation r = x_a - x_b obeys r'' = -2k r - 2b r'.
  auto pair = [&](double r, double u) {
    BodyDef a, b;
    a.body = Body{.mass = 1.0, .position = {0.5 * r, 0.0}, .velocity = {0.5 * u, 0.0}};
    b.body = Body{.mass = 1.0, .position = {-0.5 * r, 0.0}, .velocity = {-0.5 * u, 0.0}};
    const Entity ea = w.create_body(a), eb = w.create_body(b);
    w.create_link(LinkDef{ea, eb, LinkSpring{0.5 * omega * omega, 0.5 * gamma, 0.0}});
  };
  pair(1.0, 0.0);  // first column of the step's matrix: (r, r') = (1, 0)
  pair(0.0, 1.0);  // second column: (0, 1)
  w.step();
  return detail::spectral_radius(w.x()[0] - w.x()[1], w.x()[2] - w.x()[3], w.vx()[0] - w.vx()[1],
                                 w.vx()[2] - w.vx()[3]);
}

NetworkStability check_network_stability(std::span<const BodyDef> bodies,
                                         std::span<const LinkDef> links, Integrator integrator,
                                         double dt, int substeps) {
  return detail::network_stability(bodies, fixstep::index_links(links, bodies.size()), integrator,
                                   dt, substeps);
}

NetworkStability detail::network_stability(std::span<const BodyDef> bodies,
                                           std::span<const fixstep::IndexLink> links,
                                           Integrator integrator, double dt, int substeps) {
  check_step(dt, substeps);
  Assembly as(links);
  add_bodies(bodies, as);
  NetworkStability r;
  r.bodies = bodies.size(), r.springs = links.size(), r.h = dt / substeps;
  r.fastest_body = fixstep::defined_entity(0);
  add_links(bodies, links, as);
  r.stiffest_link = as.stiffest_link, r.strongest_damper = as.strongest_damper;
  const Spectrum sp = find_spectrum(as, r);
  if (overflowed(sp, r)) {
    r.verdict = Stability::unstable;
    r.radius = unbounded;
    r.message = fmt::format(
        "{} has stiffness or damping per mass beyond the range of a double, so no integrator "
        "and no step can follow it",
        network_subject(r.bodies, r.springs));
    return r;
  }
  TestModes tm{integrator, as.damped_links, {}};
  if (r.omega_max > 0.0) tm.modes.push_back({r.omega_max, r.gamma, 0.0, 0.0});
  if (r.damping_rate > 0.0) tm.modes.push_back({0.0, r.damping_rate, 0.0, 0.0});
  r.max_step = unbounded;
  r.radius = 1.0;
  if (tm.modes.empty()) return r;  // no spring and no damper: every step is stable
  tm.measure(r.h, r);
  const TestModes::Mode& b = tm.binding();
  r.damping_bound = b.omega == 0.0;
  if (r.damping_bound && as.damped) {
    r.fastest_body = fixstep::defined_entity(largest_body(as.c_op, sp.damp.vector));
  }
  judge_network(bodies, links, integrator, dt, substeps, tm, b, r);
  return r;
}

}  // namespace fixstep
