// libFuzzer target: arbitrary bytes as a scene file. A clean rejection is a SceneError; any
// other exception, a non-finite body state, a crash or a sanitizer report is a finding.
// Built by the `fuzz` preset (clang only); run as in docs/ROBUSTNESS.md, "Fuzzing".
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "scene_check.hpp"

namespace {
// FIXSTEP_FUZZ_STRICT=1 also makes these fatal: std::invalid_argument from make_world
// (scene.hpp says the loader checks every value World would refuse first), and a non-finite
// state in a scene outside the bounded range (scene_check.hpp, bounded_max).
const bool strict = [] {
  const char* v = std::getenv("FIXSTEP_FUZZ_STRICT");
  return v && std::strcmp(v, "1") == 0;
}();
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const fixstep::fuzz::Outcome out = fixstep::fuzz::check_scene_text(text);
  using fixstep::fuzz::Verdict;
  if (out.verdict == Verdict::finding || (strict && (out.verdict == Verdict::rejected_by_world ||
                                                     out.verdict == Verdict::overflowed))) {
    std::fprintf(stderr, "fuzz_scene: FINDING: %s\n", out.detail.c_str());
    std::abort();
  }
  return 0;
}
