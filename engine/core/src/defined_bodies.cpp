// The links of a definition by place in its body list (fixstep/core/defined_bodies.hpp).
#include "fixstep/core/defined_bodies.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

std::vector<IndexLink> index_links(std::span<const LinkDef> links, std::size_t bodies) {
  std::vector<IndexLink> out;
  out.reserve(links.size());
  for (std::size_t i = 0; i < links.size(); ++i) {
    const LinkDef& l = links[i];
    const std::optional<std::size_t> a = defined_index(l.body_a, bodies);
    const std::optional<std::size_t> b = defined_index(l.body_b, bodies);
    if (!a || !b) {
      const Entity bad = a ? l.body_b : l.body_a;
      throw std::invalid_argument(
          fmt::format("link[{}]: body {}:{} is not one of the definition's {} bodies (use the "
                      "handles WorldDef::add_body returns)",
                      i, bad.index1, bad.generation, bodies));
    }
    out.push_back(IndexLink{*a, *b, l.spring});
  }
  return out;
}

}  // namespace fixstep
