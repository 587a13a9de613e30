// RGBA8 frames to 256-colour paletted frames for GIF with libavfilter's palettegen and
// paletteuse (internal to the GIF path of VideoWriter).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

#include "video_av.hpp"

namespace fixstep::av {

/// The filter graph `split, palettegen=stats_mode=single, paletteuse=new=1:dither=none`:
/// each frame gets the 255 colours that best cover it (median cut over its own pixels, one
/// entry kept transparent so the GIF encoder can leave unchanged pixels out) and every pixel
/// becomes its nearest palette colour (no dithering: see video_palette.cpp for the
/// measurements). Output frames are PAL8 (the palette in data[1]), in the input's order and
/// with its pts. Runs on the calling thread (one filter thread).
class GifPalette {
 public:
  /// width x height frames with pts in `time_base` (s). Throws CaptureError naming `file`
  /// when a filter is missing or the graph cannot be built.
  GifPalette(int width, int height, AVRational time_base, const std::filesystem::path& file);
  /// Feeds `rgba` (width*height*4 bytes, top row first) with pts `pts`: it is copied into a
  /// frame of the graph's. Throws CaptureError naming the file.
  void push(std::span<const std::uint8_t> rgba, std::int64_t pts);
  /// Marks the end of the input, so the graph releases the frames it still holds.
  void end();
  /// Moves the next paletted frame into `out` (pts in time_base) and returns true, or
  /// returns false when none is ready (more input needed, or the end was reached). Throws
  /// CaptureError naming the file on a filter error.
  bool pull(AVFrame* out);

 private:
  void build(int width, int height, AVRational time_base);
  int width_, height_;
  std::filesystem::path file_;
  Graph graph_;
  AVFilterContext* source_ = nullptr;  // owned by graph_
  AVFilterContext* sink_ = nullptr;    // owned by graph_
  AVRational sink_time_base_{1, 1};
  AVRational time_base_{1, 1};
  Frame input_;
};

}  // namespace fixstep::av
