// Scene files, part zero: reading the text (size, binary data, a recording given instead) and
// parsing it as TOML with the errors in plain words. Shared with input scripts
// (input_script.cpp) through scene_reader.hpp.
#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fixstep/io/file_read.hpp>

#include "scene_reader.hpp"
#include "toml_depth.hpp"

namespace fixstep {

namespace scene_detail {

namespace {

/// toml++'s "Error while parsing SCOPE: DETAIL" in plain words: the construct named as a scene
/// author writes it, "saw '\n'" as the end of the line, control characters by code point, and
/// no C++ macro names.
std::string syntax_message(std::string_view description) {
  std::string scope, detail(description);
  constexpr std::string_view lead = "Error while parsing ";
  if (description.starts_with(lead)) {
    const std::size_t colon = description.find(": ", lead.size());
    if (colon != std::string_view::npos) {
      scope = std::string(description.substr(lead.size(), colon - lead.size()));
      detail = std::string(description.substr(colon + 2));
    }
  }
  auto replace = [&](std::string_view from, std::string_view to) {
    for (std::size_t at = detail.find(from); at != std::string::npos;
         at = detail.find(from, at + to.size())) {
      detail.replace(at, from.size(), to);
    }
  };
  replace(" (TOML_MAX_NESTED_VALUES)", "");
  replace("saw '\\n'", "found the end of the line");
  replace("saw '\\r'", "found the end of the line");
  replace("expected value,", "expected a value,");
  replace("encountered end-of-file", "the file ends here");
  // "saw '\u0001'" (toml++'s escape of a control character) and "saw 'x'".
  for (std::size_t at = detail.find("saw '\\u"); at != std::string::npos;
       at = detail.find("saw '\\u", at)) {
    const std::string code = detail.substr(at + 7, 4);
    detail.replace(at, 12, fmt::format("found the control character U+{}", code));
  }
  replace("saw '", "found '");
  std::string where;
  if (scope == "key-value pair") {
    where = " in a `key = value` line";
  } else if (scope == "table header") {
    where = " in a [table] header";
  } else if (scope == "root table") {
    where = "";
  } else if (scope == "inline table") {
    where = " in an inline table { ... }";
  } else if (scope == "array") {
    where = " in an array [ ... ]";
  } else if (scope.find("integer") != std::string::npos ||
             scope.find("floating") != std::string::npos) {
    where = " in a number";
  } else if (!scope.empty()) {
    where = fmt::format(" in a {}", scope);
  }
  return fmt::format("TOML syntax error{}: {}", where, detail);
}

/// Advice for the slips a newcomer makes writing TOML, read from the text at the error:
/// arithmetic (dt = 1/60), a bare word (integrator = rk4), a colour (#ff0000) or a leading point
/// (.5) unquoted or unwritten as TOML, (x, y) for a vector, nothing after the `=`.
std::string syntax_hint(std::string_view text, std::size_t line, std::size_t column) {
  std::size_t begin = 0;
  for (std::size_t l = 1; l < line && begin != std::string_view::npos; ++l) {
    begin = text.find('\n', begin);
    if (begin != std::string_view::npos) ++begin;
  }
  if (begin == std::string_view::npos || line == 0 || column == 0) return {};
  std::string_view row = text.substr(begin, text.find('\n', begin) - begin);
  if (row.ends_with('\r')) row.remove_suffix(1);
  const std::size_t eq = row.find('=');
  if (eq == std::string_view::npos || column - 1 < eq) return {};
  auto trim = [](std::string_view v) {
    while (!v.empty() && (v.front() == ' ' || v.front() == '\t')) v.remove_prefix(1);
    while (!v.empty() && (v.back() == ' ' || v.back() == '\t')) v.remove_suffix(1);
    return v;
  };
  const std::string_view key = trim(row.substr(0, eq));
  std::string_view value = trim(row.substr(eq + 1));
  if (const std::size_t comment = value.find(" #"); comment != std::string_view::npos) {
    value = trim(value.substr(0, comment));
  }
  const char at = column - 1 < row.size() ? row[column - 1] : '\n';
  if (value.empty()) return fmt::format("; give a value after `{} =`", key);
  if (at == '/' || at == '*') {
    // "1/60": the quotient, as the shortest text that reads back as the same double.
    const std::string v(value);
    char* end = nullptr;
    const double a = std::strtod(v.c_str(), &end);
    if (*end == '/') {
      const char* rest = end + 1;
      const double b = std::strtod(rest, &end);
      if (end != rest && *end == '\0' && b != 0.0) {
        return fmt::format("; TOML has no arithmetic: write the number, e.g. {} = {}", key, a / b);
      }
    }
    return "; TOML has no arithmetic: write the number itself";
  }
  if (value.front() == '(') return "; write a vector in square brackets, e.g. [0.0, 1.0]";
  if (value.front() == '#') {
    const bool colour = (value.size() == 7 || value.size() == 9) &&
                        std::all_of(value.begin() + 1, value.end(), [](char c) {
                          return std::isxdigit(static_cast<unsigned char>(c));
                        });
    return colour ? fmt::format(
                        "; # starts a comment in TOML: put the colour in quotes, e.g. "
                        "\"{}\"",
                        value)
                  : fmt::format("; give a value after `{} =` (# starts a comment)", key);
  }
  if (value.front() == '.' || (value.front() == '-' && value.size() > 1 && value[1] == '.')) {
    return "; TOML numbers need a digit before the point, e.g. 0.5";
  }
  if (std::isalpha(static_cast<unsigned char>(value.front())) && at == value.front() &&
      value.find_first_of("\"'") == std::string_view::npos) {
    return fmt::format("; text must be in quotes, e.g. \"{}\"", value);
  }
  return {};
}

/// The entries of `dir` that are regular files, their names only.
std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code type_ec;
    if (it->is_regular_file(type_ec)) names.push_back(it->path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// "no such scene file; did you mean X?", or naming the directory that does not exist.
std::string missing_file_message(const std::filesystem::path& file, const FileKind& kind) {
  std::error_code ec;
  // A typo: the closest name in the same directory (as the reader wrote the path).
  const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : ".";
  if (file.has_parent_path() && !std::filesystem::is_directory(dir, ec)) {
    return fmt::format("no such {}: the directory {} does not exist", kind.noun,
                       file.parent_path().string());
  }
  const std::optional<std::string> best = closest(file.filename().string(), files_in(dir));
  if (!best) return fmt::format("no such {}", kind.noun);
  return fmt::format(
      "no such {}; did you mean {}?", kind.noun,
      (file.has_parent_path() ? file.parent_path() / *best : std::filesystem::path(*best))
          .string());
}

/// "is a FIFO (named pipe), not a scene file: ..." for a file that is not a regular file.
std::string not_regular_message(const std::filesystem::path& file, const FileReadError& e,
                                const FileKind& kind) {
  const std::string type = file_type_of(file);
  if (type.empty()) return e.reason();  // gone since: say what the reader saw
  return fmt::format(
      "is {}, not {} {}: only a regular file is read (a FIFO or a device could block or never "
      "end)",
      type, kind.article, kind.noun);
}

}  // namespace

toml::table parse_toml(std::string_view text, const std::string& source_name, std::size_t max_bytes,
                       const FileKind& kind) {
  if (text.size() > max_bytes) {
    throw SceneError(source_name, 0, 0, "",
                     fmt::format("file is {} bytes; {} are limited to {} bytes", text.size(),
                                 kind.plural, max_bytes));
  }
  if (text.starts_with("fixstep-recording")) {
    throw SceneError(source_name, 0, 0, "",
                     fmt::format("is a fixstep recording, not {} {}: replay it with `fixstep "
                                 "replay {}`",
                                 kind.article, kind.noun, source_name));
  }
  if (text.find('\0') != std::string_view::npos) {
    throw SceneError(source_name, 0, 0, "",
                     fmt::format("binary data (NUL byte): not a TOML {}", kind.noun));
  }
  check_toml_depth(text, source_name);  // before toml++, whose recursion it bounds
  try {
    return toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw SceneError(source_name, at.line, at.column, "",
                     syntax_message(e.description()) + syntax_hint(text, at.line, at.column));
  }
}

std::string read_text_file(const std::filesystem::path& file, std::size_t max_bytes,
                           const FileKind& kind) {
  const std::string name = file.string();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    // Name the files in it that the reader could mean (by extension), at most three.
    std::vector<std::string> inside;
    for (const std::string& f : files_in(file)) {
      if (std::filesystem::path(f).extension().string() == kind.extension)
        inside.push_back((file / f).string());
    }
    std::string list;
    for (std::size_t i = 0; i < inside.size() && i < 3; ++i) list += (i ? ", " : "") + inside[i];
    if (inside.size() > 3) list += fmt::format(" (and {} more)", inside.size() - 3);
    throw SceneError(
        name, 0, 0, "",
        fmt::format("is a directory, not {} {}{}", kind.article, kind.noun,
                    inside.empty() ? std::string() : fmt::format("; give a file in it: {}", list)));
  }
  try {
    return read_regular_file(file, max_bytes);
  } catch (const FileReadError& e) {
    switch (e.kind()) {
      case FileReadError::Kind::missing:
        throw SceneError(name, 0, 0, "", missing_file_message(file, kind));
      case FileReadError::Kind::not_regular:
        throw SceneError(name, 0, 0, "", not_regular_message(file, e, kind));
      case FileReadError::Kind::too_large:
        throw SceneError(
            name, 0, 0, "",
            fmt::format("file is larger than the {} bytes {} may have", max_bytes, kind.owner));
      case FileReadError::Kind::unreadable:
        break;
    }
    throw SceneError(name, 0, 0, "",
                     e.reason().starts_with("read error")
                         ? e.reason()
                         : fmt::format("cannot open {}: {}", kind.noun, e.reason()));
  }
}

}  // namespace scene_detail

}  // namespace fixstep
