#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <utility>

namespace fixstep::cli {

namespace {
constexpr auto redraw_every = std::chrono::milliseconds(100);
}  // namespace

Progress::Progress(std::string what, std::string unit, std::uint64_t total, bool enabled)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      start_(std::chrono::steady_clock::now()),
      line_(enabled && total > 0) {}

Progress::~Progress() {
  finish();
}

void Progress::update(std::uint64_t done) {
  if (!line_.due() && !(line_.shown() && done >= total_)) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  const double left = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
  // "ticks/s", "bodies/s"
  const std::string units =
      unit_.ends_with('y') ? unit_.substr(0, unit_.size() - 1) + "ies" : unit_ + "s";
  line_.draw(fmt::format("{}: {} {}/{} ({} %)  {:.1f} {}/s  {:.1f} s left", what_, unit_, done,
                         total_, done * 100 / total_, rate, units, left));
}

void Progress::finish() {
  line_.finish();
}

WorkProgressLine::WorkProgressLine(bool enabled)
    : enabled_(enabled),
      scope_([this](std::string_view what, std::string_view unit, std::uint64_t done,
                    std::uint64_t total) {
        if (!line_ || what != what_ || unit != unit_ || total != total_) {
          line_.reset();  // erases the line of the work before
          what_ = what, unit_ = unit, total_ = total;
          line_.emplace(what_, unit_, total, enabled_);
        }
        line_->update(done);
      }) {}

StatusLine::StatusLine(bool enabled) : shown_(enabled && isatty(fileno(stderr)) == 1) {}

StatusLine::~StatusLine() {
  finish();
}

bool StatusLine::due() const {
  return shown_ && (!drawn_ || std::chrono::steady_clock::now() - last_ >= redraw_every);
}

void StatusLine::draw(const std::string& text) {
  if (!shown_) return;
  last_ = std::chrono::steady_clock::now();
  // "\r" back to the line's start, "\x1b[K" erases what an earlier, longer line left.
  std::fputs(fmt::format("\r{}\x1b[K", text).c_str(), stderr);
  std::fflush(stderr);
  drawn_ = true;
}

void StatusLine::finish() {
  if (!drawn_) return;
  std::fputs("\r\x1b[K", stderr);
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace fixstep::cli
