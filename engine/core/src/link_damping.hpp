// Link damping for the Strang-split methods (velocity Verlet, Forest–Ruth) on a network: the
// exact damping flow of each link, composed over the links by colours. Internal to the engine:
// not installed; used by strang_network.hpp.
//
// The damping part of a linked world, B: x' = 0, v' = -C v, is a sum of per-link dampers
// (and the bodies' own γ, the diagonal G). One link alone, with x (so its direction n̂) held,
// only changes its ends' relative velocity along n̂ (the whole relative velocity for L = 0):
//   p = (u·n̂) n̂,  u = v_a - v_b,   p' = -μ p,   μ = b (1/m_a + 1/m_b),
// and keeps the momentum m_a v_a + m_b v_b. Its flow over τ is therefore exact and closed:
//   v_a += ca p,  v_b -= cb p,  ca = (1/m_a) q, cb = (1/m_b) q,  q = (e^{-μτ} - 1)/(1/m_a + 1/m_b),
// and it removes exactly ½ |p|² (1 - e^{-2μτ}) / (1/m_a + 1/m_b) of kinetic energy (J).
// Links that share no body commute, so one colour's flows (no two links of a colour share a
// body; greedy edge colouring at rebuild) are the exact flow of that colour's dampers, in any
// order and on any number of threads. A sweep C↑(τ) = C_0(τ) ... C_{q-1}(τ) (colours in
// ascending order) is a first-order approximation of e^{-τC}; its adjoint (HLW §II.3:
// Φ*(τ) = Φ(-τ)⁻¹) is the descending sweep C↓(τ), since every factor is an exact flow.
// Placed as a palindrome around the conservative velocity-Verlet step V (kick K, drift Dr),
//   S(h) = G(h/2) K(h/2) C↑(h/2) Dr(h) C↓(h/2) K(h/2) G(h/2),
// the step is symmetric (S(-h)⁻¹ = S(h)) and consistent, hence of order 2 (Hairer, Lubich &
// Wanner, Geometric Numerical Integration, 2nd ed., §II.3, Theorem 3.2; §II.5 for splitting),
// and Yoshida's triple jump of it is of order 4 (Yoshida, Phys. Lett. A 150, 262 (1990);
// HLW §II.4, Example 4.2), with no approximation of e^{-τC} at all: every factor is exact.
// Cost: the descending sweep runs in the same loop as the force pass at the new positions
// (the flow changes only v, the force reads only x), the ascending sweep is one more loop
// over the links with the directions that pass stored; Verlet's two kicks at one position
// share one force pass (first same as last). Without link damping S is the bodies' Strang
// step G K Dr K G of body_field.hpp, on the same forces in the same order: the same bits.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fixstep {

namespace {

/// Greedy edge colouring of the links (ends a[l], b[l] among n bodies), in link order: each
/// link takes the lowest colour neither end has yet. Writes the links grouped by colour
/// (by_color, link order within a colour) and the colours' offsets into it.
inline void color_links(std::size_t n, const std::vector<std::uint32_t>& a,
                        const std::vector<std::uint32_t>& b, std::vector<std::uint32_t>& offset,
                        std::vector<std::uint32_t>& by_color) {
  const std::size_t m = a.size();
  std::vector<std::uint32_t> degree(n, 0);
  for (std::size_t l = 0; l < m; ++l) ++degree[a[l]], ++degree[b[l]];
  std::uint32_t max_degree = 0;
  for (std::uint32_t d : degree) max_degree = std::max(max_degree, d);
  const std::size_t words = (2 * std::size_t{max_degree} + 63) / 64 + 1;  // 2Δ - 1 colours at most
  std::vector<std::uint64_t> used(n * words, 0);
  std::vector<std::uint32_t> color(m);
  std::uint32_t colors = 0;
  for (std::size_t l = 0; l < m; ++l) {
    const std::uint64_t* ua = &used[a[l] * words];
    const std::uint64_t* ub = &used[b[l] * words];
    std::uint32_t c = 0;
    for (std::size_t w = 0; w < words; ++w) {
      const std::uint64_t free = ~(ua[w] | ub[w]);
      if (free != 0) {
        c = static_cast<std::uint32_t>(64 * w + static_cast<std::size_t>(__builtin_ctzll(free)));
        break;
      }
    }
    color[l] = c, colors = std::max(colors, c + 1);
    used[a[l] * words + c / 64] |= std::uint64_t{1} << (c % 64);
    used[b[l] * words + c / 64] |= std::uint64_t{1} << (c % 64);
  }
  offset.assign(colors + 1, 0);
  for (std::size_t l = 0; l < m; ++l) ++offset[color[l] + 1];
  for (std::uint32_t c = 0; c < colors; ++c) offset[c + 1] += offset[c];
  by_color.resize(m);
  std::vector<std::uint32_t> fill(offset.begin(), offset.end() - 1);
  for (std::size_t l = 0; l < m; ++l) by_color[fill[color[l]]++] = static_cast<std::uint32_t>(l);
}

/// One link's exact damping flow over the τ of (ca, cb) (see the file comment), on ends a and
/// b, with direction (nx, ny) when along (L > 0), on the whole relative velocity otherwise.
/// The kinetic energy it removes, ½ |p|² (1 - e^{-2μτ}) / (1/m_a + 1/m_b) J, less the work a
/// static or kinematic end does through the damper meanwhile, is the change of its ends'
/// kinetic energy: strang_network.hpp counts it per body around the sweeps.
template <class Real>
[[gnu::always_inline]] inline void link_flow(std::uint32_t a, std::uint32_t b, bool along, Real nx,
                                             Real ny, Real ca, Real cb, Real* vx, Real* vy) {
  const Real ux = vx[a] - vx[b], uy = vy[a] - vy[b];
  Real px = ux, py = uy;
  if (along) {
    const Real s = ux * nx + uy * ny;
    px = s * nx, py = s * ny;
  }
  vx[a] += ca * px, vy[a] += ca * py;
  vx[b] -= cb * px, vy[b] -= cb * py;
}

/// The spring force of the link at index l of (k, rest) on end a (b gets the opposite), N, as
/// link_force<true, false> computes it, and its direction (0 for L = 0 or zero length).
template <class Real>
[[gnu::always_inline]] inline void spring_force(const Real* k, const Real* rest, const Real* x,
                                                const Real* y, std::size_t l, std::uint32_t a,
                                                std::uint32_t b, bool along, Real& fx, Real& fy,
                                                Real& nx, Real& ny) {
  const Real dx = x[a] - x[b], dy = y[a] - y[b];
  nx = Real(0), ny = Real(0);
  if (along) {
    const Real len = std::sqrt(dx * dx + dy * dy);
    if (len > Real(0)) nx = dx / len, ny = dy / len;
    const Real t = len > Real(0) ? k[l] * (len - rest[l]) : Real(0);
    fx = -t * nx, fy = -t * ny;
  } else {
    fx = -k[l] * dx, fy = -k[l] * dy;
  }
}

}  // namespace

}  // namespace fixstep
