#include "fixstep/capture/manifest.hpp"

#include <fmt/format.h>

#include <iterator>
#include <stdexcept>

#include "fixstep/core/step_results.hpp"

namespace fixstep {

std::filesystem::path video_manifest_path(const std::filesystem::path& video) {
  std::filesystem::path p = video;
  return p += ".frames.csv";
}

FrameManifest::FrameManifest(const std::filesystem::path& dir)
    : FrameManifest(dir / "frames.csv", ManifestLayout::frames) {}

FrameManifest::FrameManifest(std::filesystem::path file, ManifestLayout layout)
    : path_(std::move(file)), out_(path_), layout_(layout) {
  out_.append(std::string_view(layout == ManifestLayout::tiles
                                   ? "frame,tile,tick,t,alpha,state_hash,energy,balance\n"
                                   : "frame,tick,t,alpha,state_hash,energy,balance\n"));
}

namespace {
void append_state(std::string& row, const FrameState& state) {
  const World& sim = state.world;
  fmt::format_to(std::back_inserter(row), "{},{:.6f},{:.6f},{:016x},{:.9e},{:.6e}\n", sim.tick(),
                 sim.time(), state.alpha, sim.state_hash(), sim.energy().total(),
                 energy_balance(sim, state.initial_energy));
}
}  // namespace

void FrameManifest::add(std::uint64_t frame, const FrameState& state) {
  if (layout_ != ManifestLayout::frames) {
    throw std::logic_error("FrameManifest::add: a tiles manifest needs the tile index");
  }
  row_.clear();
  fmt::format_to(std::back_inserter(row_), "{},", frame);
  append_state(row_, state);
  out_.append(std::string_view(row_));
}

void FrameManifest::add(std::uint64_t frame, std::size_t tile, const FrameState& state) {
  if (layout_ != ManifestLayout::tiles) {
    throw std::logic_error("FrameManifest::add: a frames manifest has no tile column");
  }
  row_.clear();
  fmt::format_to(std::back_inserter(row_), "{},{},", frame, tile);
  append_state(row_, state);
  out_.append(std::string_view(row_));
}

void FrameManifest::commit() {
  out_.commit();
}

}  // namespace fixstep
