// A world's state as a text file (fixstep/io/state_file.hpp).
#include "fixstep/io/state_file.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "fixstep/io/file_read.hpp"

namespace fixstep {

namespace {

/// `text` read whole as a double (shortest round-trip decimals read back exactly).
bool read_double(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

bool read_u64(const std::string& text, std::uint64_t& out, int base = 10) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  const auto [p, ec] = std::from_chars(first, last, out, base);
  return ec == std::errc{} && p == last && !text.empty();
}

/// One line's failure: "FILE:LINE: WHAT".
[[noreturn]] void bad(const std::filesystem::path& file, std::size_t line,
                      const std::string& what) {
  throw std::runtime_error(fmt::format("{}:{}: {}", file.string(), line, what));
}

/// "state tick T precision f64|f32 rolling 0|1 sleep 0|1".
void read_state_line(std::istringstream& in, StateFields& f, const std::filesystem::path& file,
                     std::size_t n) {
  std::string k1, tick, k2, precision, k3, rolling, k4, sleep, extra;
  in >> k1 >> tick >> k2 >> precision >> k3 >> rolling >> k4 >> sleep;
  if (k1 != "tick" || k2 != "precision" || k3 != "rolling" || k4 != "sleep" || (in >> extra) ||
      !read_u64(tick, f.tick) || (precision != "f64" && precision != "f32") ||
      (rolling != "0" && rolling != "1") || (sleep != "0" && sleep != "1")) {
    bad(file, n, "state: wants `state tick T precision f64|f32 rolling 0|1 sleep 0|1`");
  }
  f.precision = precision == "f32" ? Precision::f32 : Precision::f64;
  f.rolling = rolling == "1";
  f.sleep = sleep == "1";
}

/// `body I "NAME" x y vx vy theta omega sleep_ticks island`.
void read_body_line(const std::string& line, StateFile& out, const std::filesystem::path& file,
                    std::size_t n) {
  const std::size_t open = line.find('"'), close = line.rfind('"');
  if (open == std::string::npos || close == open) bad(file, n, "body: wants a name in quotes");
  std::uint64_t index = 0;
  if (!read_u64(line.substr(5, open - 6), index) || index != out.fields.bodies.size()) {
    bad(file, n, fmt::format("body: wants body {} next", out.fields.bodies.size()));
  }
  std::istringstream values(line.substr(close + 1));
  std::string v[8], extra;
  for (std::string& s : v) values >> s;
  BodyState b;
  double* d[6] = {&b.x, &b.y, &b.vx, &b.vy, &b.theta, &b.omega};
  const char* field[6] = {"x", "y", "vx", "vy", "theta", "omega"};
  for (int k = 0; k < 6; ++k) {
    if (!read_double(v[k], *d[k]))
      bad(file, n, fmt::format("body {}: {} is not a number", index, field[k]));
  }
  std::uint64_t st = 0, is = 0;
  if (!read_u64(v[6], st) || !read_u64(v[7], is) || st > 0xffffffffu || is > 0xffffffffu ||
      (values >> extra)) {
    bad(file, n, fmt::format("body {}: wants sleep ticks and island, whole numbers, last", index));
  }
  b.sleep_ticks = static_cast<std::uint32_t>(st);
  b.island = static_cast<std::uint32_t>(is);
  out.fields.bodies.push_back(b);
  out.names.push_back(line.substr(open + 1, close - open - 1));
}

}  // namespace

std::string format_state_file(const StateFields& f, const std::vector<std::string>& names,
                              const std::string& title) {
  std::string out = fmt::format(
      "# {}\n# body, name, x y (m), vx vy (m/s), theta (rad), omega (rad/s), sleep ticks, island; "
      "exact\nstate tick {} precision {} rolling {} sleep {}\n",
      title, f.tick, f.precision == Precision::f32 ? "f32" : "f64", f.rolling ? 1 : 0,
      f.sleep ? 1 : 0);
  out += f.random_state ? fmt::format("random 0x{:016x}\n", *f.random_state)
                        : std::string("random not drawn\n");
  for (std::size_t i = 0; i < f.bodies.size(); ++i) {
    const BodyState& b = f.bodies[i];
    out += fmt::format("body {} \"{}\" {} {} {} {} {} {} {} {}\n", i,
                       i < names.size() ? names[i] : std::string(), b.x, b.y, b.vx, b.vy, b.theta,
                       b.omega, b.sleep_ticks, b.island);
  }
  return out;
}

StateFile read_state_file(const std::filesystem::path& file) {
  std::istringstream text(read_regular_file(file, max_state_file_bytes));
  StateFile out;
  bool have_state = false, have_random = false;
  std::string line;
  for (std::size_t n = 1; std::getline(text, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "state" && !have_state) {
      read_state_line(in, out.fields, file, n);
      have_state = true;
    } else if (key == "random" && !have_random) {
      std::string value, extra;
      in >> value;
      std::uint64_t r = 0;
      if (value == "not" && line == "random not drawn") {
        out.fields.random_state.reset();
      } else if (value.starts_with("0x") && read_u64(value.substr(2), r, 16) && !(in >> extra)) {
        out.fields.random_state = r;
      } else {
        bad(file, n, "random: wants `random 0xHEX` or `random not drawn`");
      }
      have_random = true;
    } else if (key == "body" && have_state) {
      read_body_line(line, out, file, n);
    } else {
      bad(file, n,
          fmt::format("`{}`: wants one state line, one random line, then body lines", key));
    }
  }
  if (!have_state || !have_random) bad(file, 1, "wants a state line and a random line");
  return out;
}

std::filesystem::path state_file_beside(const std::filesystem::path& recording) {
  std::filesystem::path p = recording;
  return p.replace_extension(".state");
}

std::optional<StatesBeside> compare_states_beside(const std::filesystem::path& recording_a,
                                                  const std::filesystem::path& recording_b) {
  const std::filesystem::path fa = state_file_beside(recording_a),
                              fb = state_file_beside(recording_b);
  std::error_code ec;
  if (!std::filesystem::exists(fa, ec) || !std::filesystem::exists(fb, ec)) return std::nullopt;
  try {
    const StateFile a = read_state_file(fa), b = read_state_file(fb);
    const std::string files = fmt::format("states beside them ({}, {})", fa.string(), fb.string());
    if (a.fields.tick != b.fields.tick) {
      return StatesBeside{
          fmt::format("{}: of ticks {} and {}, not compared", files, a.fields.tick, b.fields.tick)};
    }
    const std::optional<StateDifference> d = first_difference(a.fields, b.fields);
    if (!d) {
      return StatesBeside{fmt::format("{}: equal field by field at tick {}", files, a.fields.tick)};
    }
    std::string text = describe(*d);
    if (d->body < a.names.size() && !a.names[d->body].empty()) {
      // describe() without a world names no body: the file's name, as describe() writes one.
      const std::string plain = fmt::format("body {} ", d->body);
      if (text.starts_with(plain)) {
        text = fmt::format("body {} (\"{}\") {}", d->body, a.names[d->body],
                           text.substr(plain.size()));
      }
    }
    return StatesBeside{fmt::format("{}: first differ at {}", files, text)};
  } catch (const std::exception& e) {
    return StatesBeside{fmt::format("the states beside them were not compared: {}", e.what()),
                        false};
  }
}

}  // namespace fixstep
