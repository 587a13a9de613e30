// write_desync_recording and move_desync_recording (desync_recording.hpp): a free file name,
// then io's atomic write or a rename.
#include "fixstep/net/desync_recording.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <fixstep/io/recording_file.hpp>
#include <stdexcept>
#include <system_error>

namespace fixstep::net {

namespace {

/// STEM-desync-pSLOT-tTICK.rec in `dir`, or -2 .. -99 added: the first name no file or link
/// has.
std::filesystem::path free_desync_name(const std::filesystem::path& dir, const std::string& stem,
                                       std::uint8_t slot, std::uint64_t tick) {
  const std::string base =
      fmt::format("{}-desync-p{}-t{}", stem, static_cast<unsigned>(slot), tick);
  for (int n = 1; n <= 99; ++n) {
    std::filesystem::path file = dir / (n == 1 ? base + ".rec" : fmt::format("{}-{}.rec", base, n));
    std::error_code ec;
    // symlink_status: a dangling link is taken too (never written through).
    if (std::filesystem::symlink_status(file, ec).type() == std::filesystem::file_type::not_found)
      return file;
  }
  throw std::runtime_error(
      fmt::format("{}: {}.rec and -2 to -99 are all taken: no name left for the desync recording",
                  dir.string(), base));
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
