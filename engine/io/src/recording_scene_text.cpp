// The scene a recording embeds (Recording::scene_text), as the lines of its section:
//   scene_text BYTES CHECKSUM
//   |LINE
//   |LINE ...
// BYTES is the scene's size and CHECKSUM the FNV-1a (64-bit) hash of its bytes, 16 hex digits.
// Each line of the scene (its bytes split at '\n') follows as '|' and the line, with '\\' written
// "\\\\", '\r' written "\\r" and every other control character but the tab written "\\xHH", so
// that any bytes come back exactly (a CRLF scene included) and a recording converted to CRLF
// still reads: the reader drops the '\r' a conversion adds, never one of the scene's. A scene
// that ends without a newline has one line more than its newlines; BYTES tells the reader
// whether to keep the last newline.
#include <fmt/format.h>

#include <iterator>
#include <stdexcept>

#include "fixstep/core/fnv1a.hpp"
#include "fixstep/io/printable.hpp"
#include "fixstep/io/summary.hpp"
#include "recording_text.hpp"

namespace fixstep::recording_text {

std::uint64_t scene_checksum(std::string_view text) {
  return fnv1a(text);
}

void append_scene_text(std::string& out, std::string_view text) {
  if (text.size() > max_recording_scene_bytes) {
    throw std::invalid_argument(
        fmt::format("cannot embed a scene of {} bytes in a recording: at most {} bytes (the scene "
                    "size limit)",
                    text.size(), max_recording_scene_bytes));
  }
  fmt::format_to(std::back_inserter(out), "scene_text {} {}\n", text.size(),
                 hex_hash(scene_checksum(text)));
  out += '|';
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out += i + 1 < text.size() ? "\n|" : "\n";  // the newline ending the text ends its line
      continue;
    }
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '\r') {
      out += "\\r";
    } else if ((c < 0x20 && c != '\t') || c == 0x7f) {
      fmt::format_to(std::back_inserter(out), "\\x{:02x}", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.empty() || text.back() != '\n') out += '\n';
}

SceneTextDecoder::SceneTextDecoder(std::size_t bytes, std::uint64_t checksum)
    : bytes_(bytes), checksum_(checksum) {
  text_.reserve(bytes + 1);
}

namespace {
int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
}  // namespace

std::string SceneTextDecoder::take(std::string_view line) {
  if (!line.starts_with('|')) {
    return fmt::format("expected a line of the embedded scene (`|` and the line), found \"{}\"",
                       printable(line.substr(0, 40)));
  }
  for (std::size_t i = 1; i < line.size(); ++i) {
    // Each byte is checked against the size before it is appended: a line cannot make the
    // text outgrow the size its header gave (a newline may follow the last byte).
    if (text_.size() >= bytes_) {
      return fmt::format("the embedded scene's lines hold more than its {} bytes", bytes_);
    }
    const char c = line[i];
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\t') || u == 0x7f) {
      return fmt::format(
          "a control character (byte {:#04x}) at column {}: the embedded scene writes it as \\xHH",
          u, i + 1);
    }
    if (c != '\\') {
      text_ += c;
      continue;
    }
    const char e = i + 1 < line.size() ? line[i + 1] : '\0';
    if (e == '\\' || e == 'r') {
      text_ += e == 'r' ? '\r' : '\\';
      i += 1;
    } else if (e == 'x' && i + 3 < line.size() && hex_digit(line[i + 2]) >= 0 &&
               hex_digit(line[i + 3]) >= 0) {
      text_ += static_cast<char>(hex_digit(line[i + 2]) * 16 + hex_digit(line[i + 3]));
      i += 3;
    } else {
      return fmt::format(
          "an unknown escape at column {} (the embedded scene has \\\\, \\r and \\xHH only)",
          i + 1);
    }
  }
  text_ += '\n';
  return {};
}

std::string SceneTextDecoder::finish(std::string& text) {
  if (text_.size() == bytes_ + 1) text_.pop_back();  // the scene ends without a newline
  if (scene_checksum(text_) != checksum_) {
    return fmt::format(
        "the embedded scene's bytes do not match its checksum (FNV-1a {} recorded, {} read): the "
        "recording was edited or damaged",
        hex_hash(checksum_), hex_hash(scene_checksum(text_)));
  }
  text = std::move(text_);
  return {};
}

}  // namespace fixstep::recording_text
