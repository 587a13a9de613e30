// Internal to fixstep::net_app: a match's exit statuses and its refused command lines.
#pragma once

#include <stdexcept>

namespace fixstep::net::detail {

inline constexpr int exit_error = 1;   ///< as app::run: a bad scene, an unwritable file...
inline constexpr int exit_usage = 2;   ///< as app::run: a bad command line
inline constexpr int exit_desync = 5;  ///< the peers' states differed (a desync)
inline constexpr int exit_failed = 6;  ///< refused, timed out, or the other player left

/// A command line a match refuses (exit_usage).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace fixstep::net::detail
