#include "fixstep/manifest.hpp"

#include <fmt/format.h>

#include <iterator>

namespace fixstep {

FrameManifest::FrameManifest(const std::filesystem::path& dir)
    : path_(dir / "frames.csv"), out_(path_) {
  out_.append(std::string_view("frame,tick,t,alpha,state_hash,energy,balance\n"));
}

void FrameManifest::add(std::uint64_t frame, const Session& session) {
  const Simulation& sim = session.simulation();
  row_.clear();
  fmt::format_to(std::back_inserter(row_), "{},{},{:.6f},{:.6f},{:016x},{:.9e},{:.6e}\n", frame,
                 sim.tick(), sim.time(), session.alpha(), sim.state_hash(), sim.energy().total(),
                 energy_balance(sim, session.initial_energy()));
  out_.append(std::string_view(row_));
}

void FrameManifest::commit() {
  out_.commit();
}

}  // namespace fixstep
