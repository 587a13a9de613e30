// state_hashes: per-tick state hashes of a scene, one line each, for comparing runs across
// machines (tests/cross/compare_hashes.sh: x86-64 at every SIMD level and with glibc's FMA code
// paths off, aarch64 under qemu, wasm32 under node; the browser page prints the same lines).
//
//   state_hashes SCENE [--ticks N] [--every K] [--integrator NAME] [--precision f32|f64]
//                [--simd baseline|avx2|avx512] [--threads 0|1|2]
//
// Output: "TICK HASH" per line, TICK in decimal, HASH World::state_hash() in 16 lowercase
// hex digits (hex_hash): tick 0 (the loaded state), every K-th tick, and tick N (default 1000
// ticks, K = 1), no input. Exit 0; 2 for bad arguments or a scene the loader refuses (message
// on stderr); 3 for a SIMD level this CPU or build lacks; 1 when standard output cannot be
// written ("state_hashes: cannot write standard output: File too large" past `ulimit -f`,
// "Broken pipe" when its reader has gone: SIGXFSZ and SIGPIPE are ignored, write_signals.hpp).
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fixstep/core/limits.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/summary.hpp"
#include "fixstep/io/write_signals.hpp"
#include "fixstep/scene/scene.hpp"

namespace {

using namespace fixstep;

struct Options {
  std::string scene;
  std::uint64_t ticks = 1000;
  std::uint64_t every = 1;
  std::optional<Integrator> integrator;
  std::optional<Precision> precision;
  std::optional<SimdLevel> simd;
  std::optional<int> threads;  ///< WorldSettings::threads (0 = automatic)
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr,
               "state_hashes: %s\nusage: state_hashes SCENE [--ticks N] [--every K] "
               "[--integrator NAME] [--precision f32|f64] [--simd baseline|avx2|avx512] "
               "[--threads 0|1|2]\n",
               why.c_str());
  std::exit(2);
}

std::uint64_t count(std::string_view name, const char* text, std::uint64_t min, std::uint64_t max) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text, &end, 10);  // ULLONG_MAX on overflow
  if (*text < '0' || *text > '9' || *end != '\0' || v < min || v > max) {
    usage(std::string(name) + " wants an integer in " + std::to_string(min) + ".." +
          std::to_string(max) + ", got " + text);
  }
  return v;
}

std::optional<SimdLevel> parse_simd(std::string_view name) {
  for (SimdLevel l : {SimdLevel::baseline, SimdLevel::avx2, SimdLevel::avx512}) {
    if (simd_level_name(l) == name) return l;
  }
  return std::nullopt;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a.rfind("--", 0) != 0) {
      if (!o.scene.empty()) usage("two scenes given");
      o.scene = argv[i];
      continue;
    }
    if (i + 1 >= argc) usage(std::string(a) + " needs a value");
    const char* v = argv[++i];
    if (a == "--ticks") {
      o.ticks = count(a, v, 0, max_command_ticks);  // as `fixstep run --steps`
    } else if (a == "--every") {
      o.every = count(a, v, 1, max_command_ticks);
    } else if (a == "--integrator") {
      if (!(o.integrator = parse_integrator(v))) usage(std::string("unknown integrator ") + v);
    } else if (a == "--precision") {
      if (!(o.precision = parse_precision(v))) usage(std::string("unknown precision ") + v);
    } else if (a == "--threads") {
      o.threads = static_cast<int>(count(a, v, 0, 2));
    } else if (a == "--simd") {
      if (!(o.simd = parse_simd(v))) usage(std::string("unknown SIMD level ") + v);
    } else {
      usage("unknown option " + std::string(a));
    }
  }
  if (o.scene.empty()) usage("no scene given");
  return o;
}

/// A write error of standard output, with the system's reason.
class OutputError : public std::runtime_error {
 public:
  OutputError()
      : std::runtime_error(std::string("cannot write standard output: ") +
                           std::strerror(errno ? errno : EIO)) {}
};

/// Writes `text` to standard output; throws OutputError when it cannot.
void put(const std::string& text) {
  errno = 0;
  if (std::fputs(text.c_str(), stdout) == EOF) throw OutputError();
}

/// Steps the scene o.ticks ticks, printing the hash lines (buffered: one write per 4 KiB).
void run(const Options& o) {
  Scene scene = load_scene(o.scene);
  if (o.integrator) scene.def.settings.integrator = *o.integrator;
  if (o.precision) scene.def.precision = *o.precision;
  if (o.threads) scene.def.settings.threads = *o.threads;
  check_command_work(o.ticks, tick_work(scene.def),
                     "--ticks " + std::to_string(o.ticks));  // limits.hpp, as `fixstep run`
  World sim = World(scene.def);
  std::string out;
  auto line = [&] {
    out += std::to_string(sim.tick()) + ' ' + hex_hash(sim.state_hash()) + '\n';
    if (out.size() >= 4096) put(out), out.clear();
  };
  line();
  for (std::uint64_t t = 1; t <= o.ticks; ++t) {
    sim.step();
    if (t % o.every == 0 || t == o.ticks) line();
  }
  put(out);
  errno = 0;
  if (std::fflush(stdout) != 0) throw OutputError();
}

}  // namespace

int main(int argc, char** argv) {
  fixstep::ignore_write_signals();  // a write error is reported, not a death by signal
  const Options o = parse(argc, argv);
  if (o.simd) {
    if (!simd_supported(*o.simd)) {
      std::fprintf(stderr, "state_hashes: SIMD level %s not supported here\n",
                   std::string(simd_level_name(*o.simd)).c_str());
      return 3;
    }
    set_simd_level(*o.simd);
  }
  try {
    run(o);
  } catch (const OutputError& e) {
    std::fprintf(stderr, "state_hashes: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "state_hashes: %s\n", e.what());
    return 2;
  }
  return 0;
}
