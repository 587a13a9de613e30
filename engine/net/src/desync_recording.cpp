// write_desync_recording and move_desync_recording (desync_recording.hpp): a free file name,
// then io's atomic write or a rename.
#include "fixstep/net/desync_recording.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <fixstep/io/file_write.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/io/state_file.hpp>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace fixstep::net {

namespace {

/// STEM-desync-pSLOT-tTICK.EXT in `dir`, or -2 .. -99 added: the first name no file or link
/// has.
std::filesystem::path free_desync_name(const std::filesystem::path& dir, const std::string& stem,
                                       std::uint8_t slot, std::uint64_t tick,
                                       const std::string& ext = ".rec") {
  const std::string base =
      fmt::format("{}-desync-p{}-t{}", stem, static_cast<unsigned>(slot), tick);
  for (int n = 1; n <= 99; ++n) {
    std::filesystem::path file = dir / (n == 1 ? base + ext : fmt::format("{}-{}{}", base, n, ext));
    std::error_code ec;
    // symlink_status: a dangling link is taken too (never written through).
    if (std::filesystem::symlink_status(file, ec).type() == std::filesystem::file_type::not_found)
      return file;
  }
  throw std::runtime_error(
      fmt::format("{}: {}{} and -2 to -99 are all taken: no name left for the desync file",
                  dir.string(), base, ext));
}

/// The state as text (io's state file): a line per body, every value exact.
std::string state_text(const MatchPeer& peer, const StateFields& f) {
  const World& w = peer.world();  // the bodies' names (the same bodies in the same order)
  std::vector<std::string> names;
  for (const Entity e : w.bodies()) names.push_back(w.name(e));
  return format_state_file(
      f, names,
      fmt::format("fixstep desync state: slot {} after tick {} (the first tick whose state "
                  "hashes differ)",
                  static_cast<unsigned>(peer.slot()), f.tick));
}

}  // namespace

std::filesystem::path write_desync_recording(const MatchPeer& peer,
                                             const std::filesystem::path& dir,
                                             const std::string& stem) {
  const Recording rec = peer.recording();
  const std::uint64_t tick = peer.desync() ? peer.desync()->tick : rec.ticks;
  std::filesystem::path file = free_desync_name(dir, stem, peer.slot(), tick);
  write_recording(file, rec);
  return file;
}

std::optional<std::filesystem::path> write_desync_state(const MatchPeer& peer,
                                                        const std::filesystem::path& dir,
                                                        const std::string& stem) {
  const std::optional<StateFields> f = peer.desync_state();
  if (!f) return std::nullopt;
  std::filesystem::path file = free_desync_name(dir, stem, peer.slot(), f->tick, ".state");
  write_file_atomically(file, state_text(peer, *f));
  return file;
}

std::filesystem::path move_desync_recording(const std::filesystem::path& written,
                                            const std::filesystem::path& dir,
                                            const std::string& stem, std::uint8_t slot,
                                            std::uint64_t tick) {
  std::filesystem::path file = free_desync_name(dir, stem, slot, tick);
  std::error_code ec;
  std::filesystem::rename(written, file, ec);
  if (ec) {
    throw std::runtime_error(
        fmt::format("cannot rename {} to {}: {}", written.string(), file.string(), ec.message()));
  }
  return file;
}

}  // namespace fixstep::net
