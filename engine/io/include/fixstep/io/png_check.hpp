// A PNG file checked without decoding it: what a scene loader needs to refuse a bad image where
// the scene names it (the renderer decodes it when it first draws it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>

namespace fixstep {

/// A PNG file's size, px (its IHDR chunk).
struct PngSize {
  int width = 0, height = 0;
};

/// Checks `bytes` as a PNG file (PNG specification, 2nd edition, sections 5.2 to 5.6): the
/// 8-byte signature, then chunks (length, type, data, CRC-32 of type and data) up to IEND, the
/// first an IHDR of 13 bytes whose width and height are 1 .. max_image_side
/// (fixstep/core/components.hpp), at least one IDAT. Throws std::runtime_error with the reason:
/// "not a PNG file (...)", "truncated (...)", "corrupt (chunk IDAT's CRC-32 does not match)",
/// "W x H px: ...". Compressed data whose CRCs match but that does not inflate is left to the
/// decoder.
PngSize check_png(std::span<const std::uint8_t> bytes);

/// check_png of the regular file `file` (read_regular_file, at most max_image_file_bytes).
/// Throws FileReadError (file_read.hpp) when it cannot be read, std::runtime_error as
/// check_png.
PngSize check_png_file(const std::filesystem::path& file);

}  // namespace fixstep
