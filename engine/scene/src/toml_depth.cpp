// The TOML nesting bound (toml_depth.hpp): a linear scan over the text, before toml++ sees it,
// that follows what a value's depth is built from — the [table] header, the dotted key, the
// arrays and inline tables open around it — and skips strings and comments. Nothing here
// recurses, so no input can exhaust the stack; syntax is toml++'s to judge afterwards.
#include "toml_depth.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "fixstep/scene/scene.hpp"

namespace fixstep::scene_detail {

namespace {

class DepthScan {
 public:
  DepthScan(std::string_view text, const std::string& name, std::size_t max)
      : text_(text), name_(name), max_(max) {}

  void run() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '#') {
        skip_comment();
      } else if (c == '"' || c == '\'') {
        if (in_key_) key_parts_ = std::max<std::size_t>(key_parts_, 1);
        skip_string();
      } else if (in_key_) {
        key_char(c);
      } else {
        value_char(c);
      }
    }
  }

 private:
  /// An open array (close ']') or inline table (close '}') and the level of its node.
  struct Open {
    char close;
    std::size_t depth;
  };

  /// The level of the table whose keys are being read: the inline table open innermost, or
  /// the last [table] header's.
  [[nodiscard]] std::size_t container() const {
    return open_.empty() ? header_ : open_.back().depth;
  }

  void key_char(char c) {
    if (c == '\n' && open_.empty()) {
      key_parts_ = 0;
    } else if (c == '[' && open_.empty() && key_parts_ == 0) {
      header();
      return;
    } else if (c == '.') {
      key_parts_ = std::max<std::size_t>(key_parts_, 1) + 1;
      check(container() + key_parts_, "dotted key");
    } else if (c == '=') {
      value_depth_ = container() + std::max<std::size_t>(key_parts_, 1);
      in_key_ = false;
      key_parts_ = 0;
    } else if (c == '}' && !open_.empty() && open_.back().close == '}') {
      close_bracket();  // {} (an empty inline table)
    } else if (c != ' ' && c != '\t' && c != '\r' && c != '\n') {
      key_parts_ = std::max<std::size_t>(key_parts_, 1);
    }
    advance();
  }

  void value_char(char c) {
    if (c == '[' || c == '{') {
      check(value_depth_, c == '[' ? "array" : "inline table");
      open_.push_back({c == '[' ? ']' : '}', value_depth_});
      if (c == '[') {
        ++value_depth_;
      } else {
        in_key_ = true;
        key_parts_ = 0;
      }
    } else if ((c == ']' || c == '}') && !open_.empty() && open_.back().close == c) {
      close_bracket();
    } else if (c == ',' && !open_.empty()) {
      if (open_.back().close == '}') {
        in_key_ = true;
        key_parts_ = 0;
      } else {
        value_depth_ = open_.back().depth + 1;
      }
    } else if (c == '\n' && open_.empty()) {
      in_key_ = true;
      key_parts_ = 0;
    }
    advance();
  }

  void close_bracket() {
    open_.pop_back();
    in_key_ = false;  // after a value: a ',' or the end of the line comes next
    if (!open_.empty() && open_.back().close == ']') value_depth_ = open_.back().depth + 1;
  }

  /// [a.b.c] or [[a.b.c]] at the start of a line: its parts are the level of its keys.
  void header() {
    advance();
    if (pos_ < text_.size() && text_[pos_] == '[') advance();
    std::size_t parts = 1;
    while (pos_ < text_.size() && text_[pos_] != ']' && text_[pos_] != '\n') {
      if (text_[pos_] == '"' || text_[pos_] == '\'') {
        skip_string();
        continue;
      }
      if (text_[pos_] == '.') check(++parts, "table header");
      advance();
    }
    while (pos_ < text_.size() && text_[pos_] == ']') advance();
    header_ = parts;
  }

  /// "...", '...', """...""", '''...''' (a quote of three may end with up to two more quotes);
  /// an unterminated single-line string stops at the end of the line.
  void skip_string() {
    const char q = text_[pos_];
    const std::string triple(3, q);
    const bool multi = text_.substr(pos_, 3) == triple;
    for (int i = 0; i < (multi ? 3 : 1); ++i) advance();
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\\' && q == '"') {
        advance();
        if (pos_ < text_.size()) advance();
      } else if (c == '\n' && !multi) {
        return;
      } else if (c == q && !multi) {
        advance();
        return;
      } else if (c == q && text_.substr(pos_, 3) == triple) {
        for (int i = 0; i < 3; ++i) advance();
        for (int i = 0; i < 2 && pos_ < text_.size() && text_[pos_] == q; ++i) advance();
        return;
      } else {
        advance();
      }
    }
  }

  void skip_comment() {
    while (pos_ < text_.size() && text_[pos_] != '\n') advance();
  }

  /// One byte on; the column counts code points (UTF-8 continuation bytes add none).
  void advance() {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else if (pos_ + 1 < text_.size() &&
               (static_cast<unsigned char>(text_[pos_ + 1]) & 0xC0) != 0x80) {
      ++column_;
    }
    ++pos_;
  }

  void check(std::size_t depth, std::string_view what) const {
    if (depth <= max_) return;
    throw SceneError(name_, line_, column_, "",
                     fmt::format("TOML nested too deep: this {} puts a value at level {}; fixstep "
                                 "allows {} (each part of a [table] header or dotted key, and each "
                                 "[ or {{ around a value, is one level)",
                                 what, depth, max_));
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t max_;
  std::size_t pos_ = 0, line_ = 1, column_ = 1;
  std::vector<Open> open_;
  std::size_t header_ = 0;       ///< parts of the last [table] header (0: the root table)
  bool in_key_ = true;           ///< reading a key (a line, or in an inline table), not a value
  std::size_t key_parts_ = 0;    ///< parts of the key read so far (0: none yet)
  std::size_t value_depth_ = 0;  ///< the level of the value about to be read
};

}  // namespace

void check_toml_depth(std::string_view text, const std::string& source_name,
                      std::size_t max_depth) {
  DepthScan(text, source_name, max_depth).run();
}

}  // namespace fixstep::scene_detail
