// One field of the CSV files fixstep writes (run --csv, compare --csv), quoted as RFC 4180
// says: a field holding a comma, a double quote, CR or LF is enclosed in double quotes, each
// double quote in it doubled; any other field is written as it is (numbers stay bare).
#pragma once

#include <string>
#include <string_view>

namespace fixstep::cli {

/// `text` as one CSV field (RFC 4180, section 2, rules 5-7).
[[nodiscard]] inline std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace fixstep::cli
