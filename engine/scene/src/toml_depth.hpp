// The TOML nesting bound, checked on the text before toml++ parses it.
// Internal to the engine: not installed.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace fixstep::scene_detail {

/// The deepest a TOML value may sit in a scene file or input script: each part of a
/// [table] header, each part of a dotted key and each array [ ] or inline table { } around it
/// counts one level. Real scenes reach 4 (`[[body]]` → `spring.anchor` → its array);
/// toml++ 3.3.0 builds one nested table per dotted-key part and frees them recursively, so a
/// key of ~50 000 parts overflowed the stack (SIGSEGV). 64 is far above any scene and far below
/// any stack.
inline constexpr std::size_t max_toml_depth = 64;

/// Throws SceneError(source_name, line, column) at the first character that puts a value more
/// than `max_depth` levels deep (see max_toml_depth). A linear scan that knows TOML's strings
/// (basic, literal, multi-line) and comments; it judges nothing else: syntax errors are left
/// to toml++, which parses the text only after this check. Lines and columns are 1-based,
/// columns counted in code points as toml++ counts them.
void check_toml_depth(std::string_view text, const std::string& source_name,
                      std::size_t max_depth = max_toml_depth);

}  // namespace fixstep::scene_detail
