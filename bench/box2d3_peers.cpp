// The Box2D v3 releases this build has (bench/box2d3.cmake defines FIXSTEP_HAVE_BOX2D3 for
// v3.1.1 and FIXSTEP_HAVE_BOX2D32 for v3.2 where it built them), for bench_discs and bench_boxes:
// each release's steppers (box2d3_release.hpp), or an error where it was not built.
#include <fmt/format.h>

#include <limits>
#include <stdexcept>

#include "box2d3_release.hpp"
#include "boxes.hpp"
#include "discs.hpp"

#ifndef FIXSTEP_HAVE_BOX2D3
#define FIXSTEP_HAVE_BOX2D3 0
#endif
#ifndef FIXSTEP_HAVE_BOX2D32
#define FIXSTEP_HAVE_BOX2D32 0
#endif

namespace discs {

namespace {
[[noreturn]] void not_built(Box2d3Release r) {
  throw std::logic_error(fmt::format("Box2D v3.{} is not built", r == Box2d3Release::v3_1 ? 1 : 2));
}
}  // namespace

bool box2d3_built(Box2d3Release r) {
  return r == Box2d3Release::v3_1 ? FIXSTEP_HAVE_BOX2D3 != 0 : FIXSTEP_HAVE_BOX2D32 != 0;
}

const char* box2d3_key(Box2d3Release r) {
  return r == Box2d3Release::v3_1 ? "box2d3" : "box2d32";
}

std::vector<std::string> shape_stepper_keys() {
  std::vector<std::string> k = {"fixstep_t1", "fixstep_t2"};
  for (const Box2d3Release r : box2d3_releases) {
    if (!box2d3_built(r)) continue;
    k.push_back(std::string(box2d3_key(r)) + "_w1");
    k.push_back(std::string(box2d3_key(r)) + "_w2");
  }
  return k;
}

std::string shape_stepper_label(const std::string& key) {
  if (key == "fixstep_t1") return "fixstep f64, 1 thread";
  if (key == "fixstep_t2") return "fixstep f64, 2 threads";
  for (const Box2d3Release r : box2d3_releases) {
    const std::string k = box2d3_key(r);
    const std::string v = box2d3_version(r);
    if (key == k + "_w1") return fmt::format("Box2D {} (f32), 1 worker", v);
    if (key == k + "_w2") return fmt::format("Box2D {} (f32), 2 workers", v);
  }
  return key;
}

std::unique_ptr<Stepper> make_box2d3(const Scene& s, int workers, Box2d3Release r, bool sleep) {
#if FIXSTEP_HAVE_BOX2D3
  if (r == Box2d3Release::v3_1) return box2d_v3_1::make_discs(s, workers, sleep);
#endif
#if FIXSTEP_HAVE_BOX2D32
  if (r == Box2d3Release::v3_2) return box2d_v3_2::make_discs(s, workers, sleep);
#endif
  (void)s, (void)workers, (void)sleep;
  not_built(r);
}

std::string box2d3_version(Box2d3Release r) {
#if FIXSTEP_HAVE_BOX2D3
  if (r == Box2d3Release::v3_1) return box2d_v3_1::version();
#endif
#if FIXSTEP_HAVE_BOX2D32
  if (r == Box2d3Release::v3_2) return box2d_v3_2::version();
#endif
  return r == Box2d3Release::v3_1 ? "3.1.1 (not built)" : "3.2 (not built)";
}

double box2d3_linear_slop(Box2d3Release r) {
#if FIXSTEP_HAVE_BOX2D3
  if (r == Box2d3Release::v3_1) return box2d_v3_1::linear_slop();
#endif
#if FIXSTEP_HAVE_BOX2D32
  if (r == Box2d3Release::v3_2) return box2d_v3_2::linear_slop();
#endif
  (void)r;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace discs

namespace boxes {

std::unique_ptr<BoxStepper> make_box2d3_boxes(const BoxScene& s, int workers,
                                              discs::Box2d3Release r) {
#if FIXSTEP_HAVE_BOX2D3
  if (r == discs::Box2d3Release::v3_1) return discs::box2d_v3_1::make_boxes(s, workers);
#endif
#if FIXSTEP_HAVE_BOX2D32
  if (r == discs::Box2d3Release::v3_2) return discs::box2d_v3_2::make_boxes(s, workers);
#endif
  (void)s, (void)workers;
  discs::not_built(r);
}

}  // namespace boxes
