// Text from a user (a path, a name, a field of a recording) made safe to print inside a
// one-line message: a newline would split the message and a NUL would cut
// it short where it is printed as a C string.
#pragma once

#include <string>
#include <string_view>

namespace fixstep {

/// `text` with every control character (U+0000..U+001F) and DEL written as a C escape:
/// \n, \r, \t, \0, else \xHH (two lowercase hex digits). Other bytes, the backslash and UTF-8
/// included, are kept as they are. Throws nothing but std::bad_alloc.
[[nodiscard]] std::string printable(std::string_view text);

}  // namespace fixstep
