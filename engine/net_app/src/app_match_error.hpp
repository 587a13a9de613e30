// Internal to fixstep::net_app: a match's exit statuses and its refused command lines.
#pragma once

#include <stdexcept>

namespace fixstep::net::detail {

inline constexpr int exit_error = 1;  ///< as app::run: a bad scene, an unwritable file...
inline constexpr int exit_usage = 2;  ///< as app::run: a bad command line
/// The peers' states differed (a desync): app::run's "a state differs from the recording's".
inline constexpr int exit_desync = 4;
/// Refused, timed out, or the other player left: an error.
inline constexpr int exit_failed = 1;

/// A command line a match refuses (exit_usage).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace fixstep::net::detail
