// airhockey: the drawing (draw.hpp).
#include "draw.hpp"

#include <array>
#include <string>

namespace airhockey {

using fixstep::Rgba8;
using fixstep::Vec2;

namespace {

constexpr Rgba8 marking{200, 210, 230, 120}, crease{255, 255, 255, 160};
constexpr std::array<Rgba8, 2> team{Rgba8{230, 70, 70, 255}, Rgba8{70, 130, 240, 255}};

Rgba8 faded(Rgba8 c, std::uint8_t alpha) {
  return Rgba8{c.r, c.g, c.b, alpha};
}

/// The frame of player `i`'s reach (its mallet's centre stays inside, so the frame is drawn a
/// mallet's radius further out).
void draw_reach(int i, bool mine, fixstep::app::Overlay& o) {
  const Reach r = reach(i);
  const double m = mallet_radius;
  const Vec2 lo{r.lo.x - m, r.lo.y - m}, hi{r.hi.x + m, r.hi.y + m};
  const std::array<Vec2, 5> frame{lo, Vec2{hi.x, lo.y}, hi, Vec2{lo.x, hi.y}, lo};
  o.polyline(frame, mine ? 0.05 : 0.025, faded(team[static_cast<std::size_t>(i)], mine ? 200 : 90));
}

}  // namespace

void draw_table(const GameState& game, int seat, fixstep::app::Overlay& o) {
  // The table's edge and markings.
  const Vec2 corner{half_length, half_width};
  const std::array<Vec2, 5> edge{Vec2{-corner.x, -corner.y}, Vec2{corner.x, -corner.y}, corner,
                                 Vec2{-corner.x, corner.y}, Vec2{-corner.x, -corner.y}};
  o.polyline(edge, 0.08, Rgba8{230, 230, 240, 255});
  o.line({0.0, -half_width}, {0.0, half_width}, 0.04, marking);
  o.circle({0.0, 0.0}, 0.8, 0.04, marking);
  for (int i = 0; i < 2; ++i) {
    const double x = i == 0 ? -half_length : half_length;
    o.circle({x, 0.0}, goal_radius, 0.06, crease);
    o.disc({x, 0.0}, goal_radius, faded(team[static_cast<std::size_t>(i)], 50));
    draw_reach(i, i == seat, o);
  }
  // The score, large, above the table.
  const std::string score = std::to_string(game.score[0]) + " : " + std::to_string(game.score[1]);
  o.label({-0.6, half_width + 0.45}, score, 4.0, Rgba8{255, 255, 255, 255});
  for (const std::string& line : status_lines(game)) o.text(line);
}

}  // namespace airhockey
