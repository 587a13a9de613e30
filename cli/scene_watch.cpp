#include "scene_watch.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fixstep/render/render.hpp>
#include <string_view>
#include <system_error>
#include <utility>

namespace fixstep::cli {

FileStamp stamp_of(const std::string& path) {
  std::error_code ec;
  const auto mtime = std::filesystem::last_write_time(path, ec);
  if (ec) return {};
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return {};
  FileStamp s{
      .exists = true,
      .mtime_ns =
          std::chrono::duration_cast<std::chrono::nanoseconds>(mtime.time_since_epoch()).count(),
      .size = size};
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) s.inode = static_cast<std::uint64_t>(st.st_ino);
  return s;
}

FileWatch::FileWatch(std::string path, std::chrono::milliseconds interval)
    : path_(std::move(path)),
      interval_(interval),
      last_look_(Clock::now()),
      stamp_(stamp_of(path_)) {}

bool FileWatch::changed(Clock::time_point now) {
  if (now - last_look_ < interval_) return false;
  last_look_ = now;
  FileStamp seen = stamp_of(path_);
  if (seen == stamp_) return false;
  stamp_ = seen;
  return true;
}

namespace {

/// `text` with the letters the scene and stability messages use spelled in ASCII, and any
/// other non-ASCII character as '?'.
std::string ascii(std::string_view text) {
  static constexpr std::pair<std::string_view, std::string_view> spelled[] = {
      {"ω", "omega"}, {"γ", "gamma"}, {"λ", "lambda"}, {"ζ", "zeta"}, {"π", "pi"}, {"·", "*"},
      {"²", "^2"},    {"⁻¹", "^-1"},  {"—", "-"},      {"≤", "<="},   {"≥", ">="}};
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      out += c == '\t' || c == '\n' ? ' ' : static_cast<char>(c);
      ++i;
      continue;
    }
    bool known = false;
    for (const auto& [from, to] : spelled) {
      if (text.substr(i).starts_with(from)) {
        out += to, i += from.size(), known = true;
        break;
      }
    }
    if (known) continue;
    out += '?';
    for (++i; i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80;) ++i;
  }
  return out;
}

/// Whether `line` fits a frame `frame_width` px wide, with the HUD's margin on the right too.
bool fits(const std::string& line, int frame_width, float scale) {
  return Renderer::hud_width(line, scale) + 10.0f <= static_cast<float>(frame_width);
}

/// Appends `text` to `lines`, wrapped at spaces to fit a frame `frame_width` px wide; a word
/// longer than a line (a long path) is cut where the line is full.
void wrap(const std::string& text, int frame_width, float scale, std::vector<std::string>& lines) {
  std::string line;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t end = std::min(text.find(' ', i), text.size());
    const std::string word = text.substr(i, end - i);
    i = end + 1;
    if (word.empty()) continue;
    std::string joined = line;
    if (!joined.empty()) joined += ' ';
    joined += word;
    if (fits(joined, frame_width, scale)) {
      line = std::move(joined);
      continue;
    }
    if (!line.empty()) lines.push_back(line);
    line.clear();
    for (const char c : word) {
      if (!line.empty() && !fits(line + c, frame_width, scale)) lines.push_back(line), line.clear();
      line += c;
    }
  }
  if (!line.empty()) lines.push_back(line);
}

}  // namespace

std::vector<std::string> reload_error_lines(const std::string& heading, const std::string& message,
                                            int frame_width, float scale, std::size_t max_lines) {
  std::vector<std::string> lines;
  wrap(ascii(heading), frame_width, scale, lines);
  std::vector<std::string> body;
  wrap(ascii(message), frame_width, scale, body);
  if (body.size() > max_lines) {
    body.resize(max_lines - 1);
    body.emplace_back("... (the whole message is on standard error)");
  }
  lines.insert(lines.end(), body.begin(), body.end());
  return lines;
}

std::vector<std::string> loading_lines(const std::string& file, const std::string& progress,
                                       int frame_width, float scale) {
  std::vector<std::string> lines;
  wrap(ascii("LOADING " + file + "... (the world before the save runs on until it is ready)"),
       frame_width, scale, lines);
  wrap(ascii(progress), frame_width, scale, lines);
  return lines;
}

}  // namespace fixstep::cli
