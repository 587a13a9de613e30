// The work and memory limits (limits.hpp): the counts and the checks.
#include "fixstep/core/limits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

// The implicit solve's memory model (implicit_solve_bytes), from the measurements in
// docs/ROBUSTNESS.md "Limits".
// Peak RSS of one tick less that of none, grids with rest-length links (Newton, SparseLU):
// 49 MB for 2·10^4 unknowns, 176 MB for 6.3·10^4, 634 MB for 2·10^5; a least-squares fit is
// 2.4 n^1.5 + 2100 n bytes, rounded up here to stay above every measurement. Extrapolated to
// 10^6 bodies (2·10^6 unknowns) it gives 13.5 GB, the 13.7 GB Eigen was seen to ask for.
constexpr double fill_per_unknown = 3.0;      // bytes per unknown^1.5
constexpr double bytes_per_unknown = 2500.0;  // bytes per unknown

bool implicit_with_links(std::span<const LinkDef> links, const WorldSettings& settings) {
  return settings.integrator == Integrator::implicit_euler && !links.empty();
}

/// Bodies some link joins (the implicit solve's unknowns are theirs).
std::uint64_t linked_count(std::span<const BodyDef> bodies, std::span<const LinkDef> links) {
  const std::vector<bool> linked = linked_bodies(bodies.size(), links);
  return static_cast<std::uint64_t>(std::count(linked.begin(), linked.end(), true));
}

/// What one body of implicit Euler's sparse solve costs, in body-substeps of the explicit step:
/// 64·√n for n linked bodies, above both measurements here (Newton + SparseLU per substep,
/// against semi-implicit Euler's 6.6 ns per body-substep on the same net): 3.9 µs per body and
/// substep on a 10 × 10 net (≈ 580; 64·√100 = 640) and 57 µs per body on a 10^5-body grid
/// (≈ 8600; 64·√10^5 ≈ 20 000). The solve's fill-in grows as n^1.5, so its cost per body as √n.
std::uint64_t implicit_body_weight(std::uint64_t linked) {
  return static_cast<std::uint64_t>(std::ceil(64.0 * std::sqrt(static_cast<double>(linked))));
}

/// disc_work, for the resting solver's default 20 + 10 iterations, times the settings' share of
/// them beyond (ContactSettings allows up to 1000 + 1000: 67 times the sweeps).
std::uint64_t disc_weight(const WorldSettings& settings) {
  if (!settings.contacts) return disc_work;
  constexpr int defaults =
      ContactSettings::default_velocity_iterations + ContactSettings::default_position_iterations;
  const int iterations = std::max(
      settings.contacts->velocity_iterations + settings.contacts->position_iterations, defaults);
  return (disc_work * static_cast<std::uint64_t>(iterations) + defaults - 1) / defaults;
}

/// The terms of tick_work (limits.hpp), in body-substeps.
struct WorkTerms {
  std::uint64_t bodies_links = 0, implicit = 0, planes = 0, segments = 0, discs = 0;
  std::uint64_t colliders = 0, disc_count = 0;  // dynamic colliders; discs in contacts
};

WorkTerms work_terms(std::span<const BodyDef> bodies, std::span<const LinkDef> links,
                     std::span<const PlaneDef> planes, const WorldSettings& settings,
                     std::span<const SegmentDef> segments) {
  WorkTerms t;
  const auto substeps = static_cast<std::uint64_t>(std::max(settings.substeps, 1));
  t.bodies_links = (bodies.size() + links.size()) * substeps;
  if (implicit_with_links(links, settings)) {
    t.implicit = bodies.size() * implicit_body_weight(linked_count(bodies, links)) * substeps;
  }
  for (const BodyDef& b : bodies) {
    if (!b.collider) continue;
    t.colliders += b.type == BodyType::dynamic ? 1 : 0;
    t.disc_count += settings.contacts && b.collider->collide ? 1 : 0;
  }
  t.planes = t.colliders * planes.size() * plane_pair_work;
  t.segments = t.colliders * segments.size() * segment_pair_work;
  t.discs = t.disc_count * disc_weight(settings);
  return t;
}

std::string gib(std::uint64_t bytes) {
  return fmt::format("{:.3g} GiB", static_cast<double>(bytes) / double(std::uint64_t{1} << 30));
}

}  // namespace

std::uint64_t max_candidate_pairs(std::uint64_t discs) {
  const std::uint64_t cap = std::max<std::uint64_t>(64 * discs, 1'000'000);
  return discs < 2 ? 0 : std::min(cap, discs * (discs - 1) / 2);
}

std::uint64_t tick_work(std::span<const BodyDef> bodies, std::span<const LinkDef> links,
                        std::span<const PlaneDef> planes, const WorldSettings& settings,
                        std::span<const SegmentDef> segments) {
  const WorkTerms t = work_terms(bodies, links, planes, settings, segments);
  return t.bodies_links + t.implicit + t.planes + t.segments + t.discs;
}

std::uint64_t tick_work(const WorldDef& def) {
  return tick_work(def.bodies, def.links, def.planes, def.settings, def.segments);
}

std::uint64_t implicit_solve_bytes(std::span<const BodyDef> bodies, std::span<const LinkDef> links,
                                   const WorldSettings& settings) {
  if (!implicit_with_links(links, settings)) return 0;
  // The solve covers every body (world_implicit.cpp). A spring or link with a rest length makes
  // it Newton's, a SparseLU over x and y together (2 unknowns a body); else one
  // SimplicialLDLT over one unknown a body for both axes.
  const bool newton = std::any_of(links.begin(), links.end(),
                                  [](const LinkDef& l) { return l.spring.rest_length != 0.0; }) ||
                      std::any_of(bodies.begin(), bodies.end(), [](const BodyDef& b) {
                        return b.spring && b.spring->rest_length != 0.0;
                      });
  const double per_body = newton ? 2.0 : 1.0;
  const double linked = static_cast<double>(linked_count(bodies, links)) * per_body;
  const double all = static_cast<double>(bodies.size()) * per_body;
  // Fitted to peak RSS on square grids (ROBUSTNESS.md, "Limits"), rounded up: fill-in that
  // grows as n^1.5 in the linked unknowns, and the matrix, vectors and triplets, linear in all.
  const double bytes = fill_per_unknown * linked * std::sqrt(linked) + bytes_per_unknown * all;
  return static_cast<std::uint64_t>(std::min(bytes, 1e19));
}

bool implicit_solve_within_limits(std::span<const BodyDef> bodies, std::span<const LinkDef> links,
                                  const WorldSettings& settings) {
  return !implicit_with_links(links, settings) ||
         (linked_count(bodies, links) <= max_implicit_bodies &&
          implicit_solve_bytes(bodies, links, settings) <= max_implicit_solve_bytes);
}

void check_world_limits(std::span<const BodyDef> bodies, std::span<const LinkDef> links,
                        std::span<const PlaneDef> planes, const WorldSettings& settings,
                        std::span<const SegmentDef> segments) {
  if (implicit_with_links(links, settings) && linked_count(bodies, links) > max_implicit_bodies) {
    throw LimitError(fmt::format(
        "implicit_euler on {} linked bodies: at most {} may be solved together (one sparse "
        "factorisation takes about a second at 40 000 here, and a stop request waits for it): "
        "use semi_implicit_euler with substeps (stable where the stability guard says) for a "
        "network this large",
        linked_count(bodies, links), max_implicit_bodies));
  }
  const std::uint64_t bytes = implicit_solve_bytes(bodies, links, settings);
  if (bytes > max_implicit_solve_bytes) {
    throw LimitError(fmt::format(
        "implicit_euler on {} linked bodies would need about {} for its sparse factorisation "
        "(at most {} allowed): use semi_implicit_euler with substeps (stable where the "
        "stability guard says) for a network this large",
        linked_count(bodies, links), gib(bytes), gib(max_implicit_solve_bytes)));
  }
  const WorkTerms t = work_terms(bodies, links, planes, settings, segments);
  const std::uint64_t work = t.bodies_links + t.implicit + t.planes + t.segments + t.discs;
  if (work > max_tick_work) {
    std::string terms =
        fmt::format("{} bodies + {} links{} × {} substeps", bodies.size(), links.size(),
                    t.implicit > 0 ? fmt::format(" + {} × {} (implicit solve)", bodies.size(),
                                                 implicit_body_weight(linked_count(bodies, links)))
                                   : "",
                    settings.substeps);
    if (t.planes > 0) {
      terms += fmt::format(" + {} colliders × {} planes", t.colliders, planes.size());
    }
    if (t.segments > 0) {
      terms += fmt::format(" + {} colliders × {} segments × {}", t.colliders, segments.size(),
                           segment_pair_work);
    }
    if (t.discs > 0) {
      terms += fmt::format(" + {} discs × {} (contacts)", t.disc_count, disc_weight(settings));
    }
    const std::uint64_t most =
        std::max({t.bodies_links, t.implicit, t.planes, t.segments, t.discs});
    throw LimitError(fmt::format(
        "{} = {} body-substeps per tick; a tick may do at most {:.0e} (about 10 s of CPU): use "
        "fewer {}",
        terms, work, double(max_tick_work),
        most == t.segments ? "segments (a polyline's points) or fewer colliders"
        : most == t.planes ? "planes or fewer colliders"
        : most == t.discs  ? "discs"
                           : "substeps or fewer bodies"));
  }
}

}  // namespace fixstep
