// SoftRasteriser (soft_shapes.hpp). Each pair of triangles that makes one convex quad with one
// affine map of its attributes (a line's, a disc's, a glyph's quad) is drawn as that quad: one
// set-up and one span per row instead of two (SoftPiece, soft_piece.cpp). Pieces are sorted into
// bands of rows and drawn band by band, so that a band's pixels stay in cache, the bands shared
// between two threads.
#include "soft_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <system_error>
#include <thread>

#include "soft_piece.hpp"

namespace fixstep::detail {

namespace {

constexpr int band_rows = 16;              // rows of a band: 80 KB of a 1280 px frame
constexpr std::uint32_t ahead_pieces = 2;  // how far ahead the pieces' pixels are asked for

}  // namespace

bool within_soft_reach(std::span<const CanvasVertex> vertices) {
  return std::all_of(vertices.begin(), vertices.end(), [](const CanvasVertex& v) {
    return std::abs(v.x) <= soft_reach_px && std::abs(v.y) <= soft_reach_px;  // false for NaN
  });
}

/// The second thread: it draws bands beside the caller of draw() (SoftRasteriser::run_bands).
struct SoftRasteriser::Crew {
  std::mutex mutex;
  std::condition_variable wake, done;
  std::uint64_t job = 0;  ///< frames handed out
  bool busy = false;      ///< the helper has not finished the current frame's bands
  bool stop = false;
  std::thread thread;
};

SoftRasteriser::SoftRasteriser() = default;

SoftRasteriser::~SoftRasteriser() {
  if (!crew_) return;
  {
    const std::lock_guard lock(crew_->mutex);
    crew_->stop = true;
  }
  crew_->wake.notify_one();
  crew_->thread.join();
}

void SoftRasteriser::clear() {
  pieces_.clear();
}

namespace {

/// Whether (a, b, c), (a, c, d) is an axis-aligned rectangle of area with opposite corners a
/// and c (snapped: p), solid (no shape coordinates, no hole) and of one colour.
bool solid_rect(const CanvasVertex& a, const CanvasVertex& b, const CanvasVertex& c,
                const CanvasVertex& d, const std::int64_t (&p)[4][2]) {
  const bool sides =
      (p[0][0] == p[3][0] && p[1][0] == p[2][0] && p[0][1] == p[1][1] && p[2][1] == p[3][1]) ||
      (p[0][0] == p[1][0] && p[2][0] == p[3][0] && p[0][1] == p[3][1] && p[1][1] == p[2][1]);
  if (!sides || p[0][0] == p[2][0] || p[0][1] == p[2][1]) return false;
  for (const CanvasVertex* v : {&a, &b, &c, &d}) {
    if (v->u != 0.0f || v->v != 0.0f || !(v->fill < soft_no_hole) || v->r != a.r || v->g != a.g ||
        v->b != a.b || v->a != a.a) {
      return false;
    }
  }
  return true;
}

/// Whether triangles (a, b, c) and (a, c, d) make one convex quad a b c d on which d's attributes
/// are those the plane through a, b, c gives it, within float rounding (then GL's two planes
/// are one, and the quad can be drawn as one piece).
bool one_quad(const CanvasVertex& a, const CanvasVertex& b, const CanvasVertex& c,
              const CanvasVertex& d, const std::int64_t (&p)[4][2]) {
  if (a.fill != d.fill || c.fill != d.fill) return false;
  const std::int64_t turns[4] = {soft_cross(p[0], p[1], p[2]), soft_cross(p[1], p[2], p[3]),
                                 soft_cross(p[2], p[3], p[0]), soft_cross(p[3], p[0], p[1])};
  const bool left = turns[0] > 0, right = turns[0] < 0;
  for (const std::int64_t t : turns) {
    if (!((left && t > 0) || (right && t < 0))) return false;  // not strictly convex
  }
  // d = a + s (b - a) + t (c - a): its attributes predicted likewise.
  const double bx = double(b.x) - a.x, by = double(b.y) - a.y, cx = double(c.x) - a.x,
               cy = double(c.y) - a.y, dx = double(d.x) - a.x, dy = double(d.y) - a.y;
  const double inv_det = 1.0 / (bx * cy - cx * by);
  const double s = (dx * cy - cx * dy) * inv_det, t = (bx * dy - dx * by) * inv_det;
  auto fits = [&](double fa, double fb, double fc, double fd, double tolerance) {
    return std::abs(fa + s * (fb - fa) + t * (fc - fa) - fd) <= tolerance;
  };
  const double uv_tolerance =
      1e-6 * (1.0 + std::max({std::abs(a.u), std::abs(a.v), std::abs(b.u), std::abs(b.v),
                              std::abs(c.u), std::abs(c.v)}));
  if (!fits(a.u, b.u, c.u, d.u, uv_tolerance) || !fits(a.v, b.v, c.v, d.v, uv_tolerance)) {
    return false;
  }
  return fits(a.r, b.r, c.r, d.r, 1e-3) && fits(a.g, b.g, c.g, d.g, 1e-3) &&
         fits(a.b, b.b, c.b, d.b, 1e-3) && fits(a.a, b.a, c.a, d.a, 1e-3);
}

}  // namespace

void SoftRasteriser::add(std::span<const CanvasVertex> vertices,
                         std::span<const std::uint32_t> indices, PixelBox box) {
  for (std::size_t k = 0; k + 2 < indices.size(); k += 3) {
    const CanvasVertex* v[4] = {&vertices[indices[k]], &vertices[indices[k + 1]],
                                &vertices[indices[k + 2]], nullptr};
    std::int64_t p[4][2] = {};
    for (int n = 0; n < 3; ++n) p[n][0] = soft_snap(v[n]->x), p[n][1] = soft_snap(v[n]->y);
    int corners = 3;
    // The renderer's quads: (a, b, c) then (a, c, d).
    if (k + 5 < indices.size() && indices[k + 3] == indices[k] &&
        indices[k + 4] == indices[k + 2]) {
      const CanvasVertex* d = &vertices[indices[k + 5]];
      p[3][0] = soft_snap(d->x);
      p[3][1] = soft_snap(d->y);
      if (solid_rect(*v[0], *v[1], *v[2], *d, p)) {  // a glyph's, a panel's: no edges needed
        const std::int64_t x0 = std::min(p[0][0], p[2][0]), x1 = std::max(p[0][0], p[2][0]);
        const std::int64_t y0 = std::min(p[0][1], p[2][1]), y1 = std::max(p[0][1], p[2][1]);
        pieces_.emplace_back();
        if (!pieces_.back().set_up_rect(*d, x0, y0, x1, y1, box)) pieces_.pop_back();
        k += 3;
        continue;
      }
      if (one_quad(*v[0], *v[1], *v[2], *d, p)) {
        v[3] = d;
        corners = 4;
        k += 3;
      }
    }
    pieces_.emplace_back();
    if (!pieces_.back().set_up(v, p, corners, box)) pieces_.pop_back();
  }
}

void SoftRasteriser::draw(std::span<std::uint8_t> pixels, int width, int height) {
  // Bands of band_rows rows, aligned to the GL framebuffer's 2x2 quads (which pair rows 2k and
  // 2k + 1 counted from the bottom row): band b is rows [b band_rows - odd, ...).
  frame_ = pixels;
  width_ = width;
  height_ = height;
  const int odd = height & 1;
  bands_ = (height + odd + band_rows - 1) / band_rows;
  auto band_of = [&](int row) { return (row + odd) / band_rows; };
  // Counting sort of the pieces into the bands they reach, each band's in their order:
  // band b's are band_list_[band_start_[b], band_start_[b + 1]).
  band_start_.assign(std::size_t(bands_) + 1, 0);
  for (const SoftPiece& t : pieces_) {
    for (int b = band_of(t.row0); b <= band_of(t.row1); ++b) ++band_start_[std::size_t(b) + 1];
  }
  for (int b = 0; b < bands_; ++b) band_start_[std::size_t(b) + 1] += band_start_[std::size_t(b)];
  band_list_.resize(band_start_[std::size_t(bands_)]);
  band_next_.assign(band_start_.begin(), band_start_.end() - 1);
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    const SoftPiece& t = pieces_[k];
    for (int b = band_of(t.row0); b <= band_of(t.row1); ++b) {
      band_list_[band_next_[std::size_t(b)]++] = static_cast<std::uint32_t>(k);
    }
  }
  next_band_.store(0);
  // Bands touch disjoint rows, so whichever thread draws a band, its pixels are the same.
  const bool helped = pieces_.size() >= min_pieces_for_crew && start_crew();
  if (helped) {
    {
      const std::lock_guard lock(crew_->mutex);
      ++crew_->job;
      crew_->busy = true;
    }
    crew_->wake.notify_one();
  }
  run_bands();
  if (helped) {
    std::unique_lock lock(crew_->mutex);
    crew_->done.wait(lock, [&] { return !crew_->busy; });
  }
  clear();
}

bool SoftRasteriser::start_crew() {
#ifdef __EMSCRIPTEN__
  return false;  // no threads in the page (and no CPU drawing: Renderer::first_soft_batch)
#else
  if (crew_) return true;
  if (std::thread::hardware_concurrency() < 2) return false;
  crew_ = std::make_unique<Crew>();
  try {
    crew_->thread = std::thread([this] {
      std::uint64_t seen = 0;
      for (;;) {
        {
          std::unique_lock lock(crew_->mutex);
          crew_->wake.wait(lock, [&] { return crew_->stop || crew_->job != seen; });
          if (crew_->stop) return;
          seen = crew_->job;
        }
        run_bands();
        {
          const std::lock_guard lock(crew_->mutex);
          crew_->busy = false;
        }
        crew_->done.notify_one();
      }
    });
  } catch (const std::system_error&) {  // no thread to be had: the caller draws alone
    crew_.reset();
    return false;
  }
  return true;
#endif
}

void SoftRasteriser::ahead(const SoftPiece& t, int first, int last) const {
  const std::size_t row = std::size_t(width_) * 4;
  const std::size_t x0 = std::size_t(t.col0) * 4, x1 = std::size_t(t.col1) * 4 + 3;
  for (int j = std::max({first, t.row0, 0}); j <= std::min(last, t.row1); ++j) {
    const auto p = reinterpret_cast<std::uintptr_t>(frame_.data() + std::size_t(j) * row);
    for (std::uintptr_t a = (p + x0) & ~std::uintptr_t(63); a <= p + x1; a += 64) {
      __builtin_prefetch(reinterpret_cast<const void*>(a), 1);
    }
  }
}

void SoftRasteriser::run_bands() {
  const int odd = height_ & 1;
  for (int b = next_band_.fetch_add(1); b < bands_; b = next_band_.fetch_add(1)) {
    const int first = b * band_rows - odd, last = first + band_rows - 1;
    // The frame comes from OSMesa's copy of it, mostly out of the first two levels of cache:
    // the lines a piece covers are asked for two pieces before it is drawn (the whole band at
    // once, or a band ahead, is too much at a time to arrive in time and stay).
    const std::uint32_t begin = band_start_[std::size_t(b)], end = band_start_[std::size_t(b) + 1];
    for (std::uint32_t n = begin; n < std::min(begin + ahead_pieces, end); ++n) {
      ahead(pieces_[band_list_[n]], first, last);
    }
    for (std::uint32_t n = begin; n < end; ++n) {
      if (n + ahead_pieces < end) ahead(pieces_[band_list_[n + ahead_pieces]], first, last);
      const SoftPiece& t = pieces_[band_list_[n]];
      if (t.solid) {
        t.draw_solid(frame_.data(), width_, first, last);
      } else {
        // Whole quads: from the top of the first pair of rows the piece reaches.
        const int top = std::max(first, t.row0 - ((t.row0 + odd) & 1));
        t.draw_shaded(frame_.data(), width_, top, std::min(last, t.row1));
      }
    }
  }
}

}  // namespace fixstep::detail
