// The stability guard's messages, for single bodies and networks alike (stability_verdict.hpp).
#include "stability_verdict.hpp"

#include <fmt/format.h>

namespace fixstep::detail {

namespace {

/// The rates that are not zero, each "name = value unit, ".
std::string listed_rates(const GuardFinding& f) {
  std::string rates;
  for (const NamedRate& r : f.rates) {
    if (r.name && r.value > 0.0) rates += fmt::format("{} = {:.4g} {}, ", r.name, r.value, r.unit);
  }
  return rates;
}

/// "S is unstable with M at dt = D s[ and substeps = N]: W = V exceeds the B V_max (...)".
std::string unstable_message(const GuardFinding& f) {
  const std::string growth = std::isinf(f.radius) && f.infinite_diverges
                                 ? std::string("it diverges beyond it")
                                 : fmt::format("growth {:.6g}x per step", f.radius);
  return fmt::format(
      "{} is unstable with {} at dt = {:g} s{}: {} = {:.4g} exceeds the {} {:.4g} ({}{}{}{})",
      f.subject, f.method, f.dt,
      f.substeps > 1 ? fmt::format(" and substeps = {}", f.substeps) : std::string(), f.step_name,
      f.rate * f.h, f.bound_name, f.rate * f.named_max_step, f.naming, f.naming.empty() ? "" : "; ",
      listed_rates(f), growth);
}

/// "S is unstable with M at every dt: its energy grows each step (W = V, growth Rx per step)".
std::string unstable_everywhere_message(const GuardFinding& f) {
  return fmt::format(
      "{} is unstable with {} at every dt: its energy grows each step ({} = {:.4g}, growth "
      "{:.6g}x per step{}{})",
      f.subject, f.method, f.step_name, f.rate * f.h, f.radius, f.naming.empty() ? "" : "; ",
      f.naming);
}

/// "S is within 10 % of M's B: W = V, bound V_max[ (...)]".
std::string near_limit_message(const GuardFinding& f) {
  return fmt::format("{} is within 10 % of {}'s {}: {} = {:.4g}, bound {:.4g}{}", f.subject,
                     f.method, f.bound_name, f.step_name, f.rate * f.h, f.rate * f.named_max_step,
                     f.naming.empty() ? std::string() : fmt::format(" ({})", f.naming));
}

}  // namespace

std::string guard_message(Stability verdict, const GuardFinding& f) {
  switch (verdict) {
    case Stability::stable:
      return {};
    case Stability::near_limit:
      return near_limit_message(f);
    case Stability::unstable:
      return f.max_step > 0.0 ? unstable_message(f) : unstable_everywhere_message(f);
  }
  return {};
}

std::string stable_from(int min_substeps, double max_step, int substeps) {
  if (min_substeps <= 0) return {};
  return fmt::format("; stable from substeps = {} (dt <= {:.4g} s)", min_substeps,
                     max_step * substeps);
}

}  // namespace fixstep::detail
