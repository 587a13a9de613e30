// bench_discs' report, internal to discs_report.cpp and discs_report_box2d3.cpp: the helpers
// both use and the parts on Box2D v3.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <functional>
#include <limits>
#include <string>

#include "discs.hpp"

namespace discs::report {

inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// The run's cases by scene, stepper key and N.
struct View {
  const Results& r;
  [[nodiscard]] const CaseResult* at(SceneKind s, const std::string& key, std::int64_t n) const {
    const auto it = r.cases.find(fmt::format("{}/{}/{}", scene_name(s), key, n));
    return it == r.cases.end() ? nullptr : &it->second;
  }
  [[nodiscard]] double ns(SceneKind s, const std::string& key, std::int64_t n) const {
    const CaseResult* c = at(s, key, n);
    return c ? c->ns_per_body_step : nan;
  }
};

/// Appends a line of markdown.
using Line = std::function<void(const std::string&)>;

[[nodiscard]] std::string size_text(std::int64_t n);                ///< "10^4", else the number
[[nodiscard]] std::string num(double v, const char* f = "{:.3g}");  ///< "–" for NaN
[[nodiscard]] std::string repetitions_text(const Results& r);
[[nodiscard]] std::string verdict(bool measured, bool ok);  ///< "yes", "**no**", "not measured"

// discs_report_box2d3.cpp:
/// The issue-33 table: fixstep on 1 and 2 threads beside Box2D v3.1.1 and v3.2 on 1 and 2
/// workers (v3.2's columns where it was built).
void box2d3_table(const View& v, const Line& line);
/// The report's first line's part on Box2D v3: each release built, its substeps and slop.
[[nodiscard]] std::string box2d3_summary();
/// Issue 33's targets against Box2D v3.1.1, where it was built.
void box2d3_targets(const View& v, const Line& line);
void box2d32_targets(const View& v, const Line& line);

}  // namespace discs::report
