// PNG capture and atomic files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <latch>
#include <random>
#include <string>
#include <thread>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "fixstep/capture/capture.hpp"

namespace fixstep {
namespace {

std::filesystem::path temp_dir(const char* name) {
  auto d = std::filesystem::temp_directory_path() /
           ("fixstep_test_" + std::string(name) + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

TEST(Capture, PngRoundTripsExactly) {
  const auto dir = temp_dir("png");
  const int w = 37, h = 11;  // odd sizes catch stride mistakes
  std::vector<std::uint8_t> rgba(w * h * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = static_cast<std::uint8_t>(i * 7 + 3);
  const auto file = frame_path(dir, 42);
  EXPECT_EQ(file.filename(), "frame_000042.png");
  write_png(file, w, h, rgba);
  int rw = 0, rh = 0, channels = 0;
  stbi_uc* back = stbi_load(file.c_str(), &rw, &rh, &channels, 4);
  ASSERT_NE(back, nullptr);
  EXPECT_EQ(rw, w);
  EXPECT_EQ(rh, h);
  EXPECT_TRUE(std::equal(rgba.begin(), rgba.end(), back));
  stbi_image_free(back);
  // no temporary left behind
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
  std::filesystem::remove_all(dir);
}

/// A test picture like a rendered frame with some noise: a flat background, a gradient, hard
/// edged rectangles, and a noisy band (so every deflate path — literals, matches, stored — is
/// exercised). Width*height RGBA8, top row first.
std::vector<std::uint8_t> test_picture(int w, int h, unsigned seed) {
  std::vector<std::uint8_t> p(static_cast<std::size_t>(w) * h * 4);
  std::mt19937 rng(seed);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* q = &p[(static_cast<std::size_t>(y) * w + x) * 4];
      q[0] = 20, q[1] = 24, q[2] = 32, q[3] = 255;
      if (y < h / 4)
        q[0] = static_cast<std::uint8_t>(255 * x / w), q[1] = static_cast<std::uint8_t>(y);
      if ((x / 9 + y / 7) % 5 == 0) q[1] = 200, q[2] = 90;
      if (y > h / 2 && y < h / 2 + 6) {
        for (int c = 0; c < 4; ++c) q[c] = static_cast<std::uint8_t>(rng());
      }
    }
  }
  return p;
}

/// Decodes PNG bytes with stb_image (RGBA); empty if they are not a PNG of w x h.
std::vector<std::uint8_t> decode(std::span<const std::uint8_t> png, int w, int h) {
  int rw = 0, rh = 0, channels = 0;
  stbi_uc* back =
      stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &rw, &rh, &channels, 4);
  if (!back || rw != w || rh != h) {
    stbi_image_free(back);
    return {};
  }
  std::vector<std::uint8_t> out(back, back + static_cast<std::size_t>(w) * h * 4);
  stbi_image_free(back);
  return out;
}

/// The PNG colour type (IHDR's 10th data byte): 2 RGB, 6 RGBA.
int png_colour_type(std::span<const std::uint8_t> png) {
  return png.size() > 25 ? png[25]
                         : -1;  // signature 8, length 4, "IHDR" 4, width 4, height 4, depth 1
}

TEST(Capture, AnOpaqueImageIsWrittenAsRgbAndRoundTripsExactly) {
  // Every alpha 255 (every rendered frame): colour type 2, a quarter fewer bytes to compress,
  // decoding to the same RGBA. Widths 1 to 9 and 37 (rows of every length mod 4, each pixel
  // written over the last one's alpha, the last into the spare byte); one alpha of 254
  // keeps the image RGBA (type 6).
  for (const int w : {1, 2, 3, 4, 5, 6, 7, 8, 9, 37}) {
    const int h = 5;
    std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4);
    for (std::size_t i = 0; i < rgba.size(); ++i) {
      rgba[i] = i % 4 == 3 ? 255 : static_cast<std::uint8_t>(i * 37 + 11);
    }
    PngEncoder encoder;
    const auto opaque = encoder.encode(w, h, rgba);
    std::vector<std::uint8_t> png(opaque.begin(), opaque.end());
    EXPECT_EQ(png_colour_type(png), 2) << "width " << w;
    EXPECT_EQ(decode(png, w, h), rgba) << "width " << w;
    rgba[rgba.size() - 1] = 254;  // the last pixel's alpha
    const auto translucent = encoder.encode(w, h, rgba);
    png.assign(translucent.begin(), translucent.end());
    EXPECT_EQ(png_colour_type(png), 6) << "width " << w;
    EXPECT_EQ(decode(png, w, h), rgba) << "width " << w;
  }
}

std::vector<std::uint8_t> read_all(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(Capture, EveryLevelRoundTripsExactly) {
  const int w = 203, h = 97;  // odd width: rows are not a multiple of 8 bytes
  const auto picture = test_picture(w, h, 1);
  std::vector<std::size_t> sizes;
  for (int level : {0, 1, 2, 6, 9, 12}) {
    PngEncoder encoder(PngSettings{.level = level});
    EXPECT_EQ(encoder.options().level, level);
    const auto png = encoder.encode(w, h, picture);
    static constexpr std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    ASSERT_GE(png.size(), 8u);
    EXPECT_EQ(std::memcmp(png.data(), signature, 8), 0) << "level " << level;
    EXPECT_EQ(decode(png, w, h), picture) << "level " << level;
    sizes.push_back(png.size());
  }
  // The level reaches libdeflate: level 0 stores (larger than the raw pixels), 12 compresses.
  EXPECT_GT(sizes.front(), picture.size());
  EXPECT_LT(sizes.back(), sizes.front() / 2);
}

/// CRC-32 as the PNG specification defines it (polynomial 0xEDB88320, reflected, initial and
/// final value 0xFFFFFFFF), bit by bit: an independent reference for the encoder's chunk CRCs.
std::uint32_t reference_crc32(const std::uint8_t* p, std::size_t n) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

TEST(Capture, EveryChunkCarriesTheStandardCrc32) {
  // stb_image does not check CRCs when decoding, so a wrong CRC hook would pass the round
  // trips above; stricter readers (libpng) reject such files.
  const int w = 203, h = 97;
  const auto picture = test_picture(w, h, 3);
  for (int level : {0, 1, 6}) {
    PngEncoder encoder(PngSettings{.level = level});
    const auto png = encoder.encode(w, h, picture);
    std::vector<std::string> types;
    std::size_t i = 8;
    while (i + 12 <= png.size()) {
      const std::size_t len = (std::size_t{png[i]} << 24) | (std::size_t{png[i + 1]} << 16) |
                              (std::size_t{png[i + 2]} << 8) | png[i + 3];
      ASSERT_LE(i + 12 + len, png.size()) << "level " << level;
      const std::uint8_t* c = &png[i + 8 + len];
      const std::uint32_t stored = (std::uint32_t{c[0]} << 24) | (std::uint32_t{c[1]} << 16) |
                                   (std::uint32_t{c[2]} << 8) | c[3];
      types.emplace_back(reinterpret_cast<const char*>(&png[i + 4]), 4);
      EXPECT_EQ(stored, reference_crc32(&png[i + 4], len + 4))
          << "level " << level << ", chunk " << types.back();
      i += 12 + len;
    }
    EXPECT_EQ(i, png.size()) << "level " << level;
    EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "IDAT", "IEND"})) << "level " << level;
  }
}

TEST(Capture, EncoderIsReusableAcrossImagesAndSizes) {
  PngEncoder encoder;
  EXPECT_EQ(encoder.options().level, default_png_level);
  for (unsigned seed = 0; seed < 4; ++seed) {
    const int w = 16 + 13 * static_cast<int>(seed), h = 40 - 7 * static_cast<int>(seed);
    const auto picture = test_picture(w, h, seed);
    EXPECT_EQ(decode(encoder.encode(w, h, picture), w, h), picture) << "image " << seed;
  }
  const auto dir = temp_dir("encoder");
  const auto picture = test_picture(64, 48, 9);
  encoder.write(dir / "a.png", 64, 48, picture);
  write_png(dir / "b.png", 64, 48, picture, PngSettings{.level = 6});
  EXPECT_EQ(decode(read_all(dir / "a.png"), 64, 48), picture);
  EXPECT_EQ(decode(read_all(dir / "b.png"), 64, 48), picture);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 2);
  std::filesystem::remove_all(dir);
}

TEST(Capture, LevelOutOfRangeIsRefusedWithTheRange) {
  for (int level : {-1, 13, 1000}) {
    try {
      PngEncoder encoder(PngSettings{.level = level});
      FAIL() << "level " << level << " accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("PNG level " + std::to_string(level) + " "), std::string::npos) << what;
      EXPECT_NE(what.find("0..12"), std::string::npos) << what;
    }
    EXPECT_FALSE(png_level_error(level).empty());
  }
  EXPECT_EQ(png_level_error(0), "");
  EXPECT_EQ(png_level_error(12), "");
  const auto dir = temp_dir("badlevel");
  EXPECT_THROW(
      write_png(dir / "x.png", 2, 2, std::vector<std::uint8_t>(16), PngSettings{.level = 13}),
      std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
  std::filesystem::remove_all(dir);
}

TEST(Capture, EncodersOnSeveralThreadsGiveTheSameBytes) {
  // Each thread has its own encoder; the stb globals and the compressor binding must not leak
  // between threads (levels differ per thread, so a shared compressor would change the bytes).
  const int w = 320, h = 180;
  const auto picture = test_picture(w, h, 3);
  std::vector<std::vector<std::uint8_t>> expected;
  for (int level : {1, 9}) {
    PngEncoder e(PngSettings{.level = level});
    const auto png = e.encode(w, h, picture);
    expected.emplace_back(png.begin(), png.end());
  }
  ASSERT_NE(expected[0], expected[1]);
  std::vector<int> mismatches(2, 0);
  std::vector<std::thread> threads;
  std::latch start(2);  // both threads encode at the same time
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      PngEncoder e(PngSettings{.level = t == 0 ? 1 : 9});
      start.arrive_and_wait();
      for (int i = 0; i < 30; ++i) {
        const auto png = e.encode(w, h, picture);
        if (!std::equal(png.begin(), png.end(), expected[t].begin(), expected[t].end())) {
          ++mismatches[t];
        }
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(mismatches, std::vector<int>(2, 0));
}

/// The names in `dir`, sorted.
std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(FrameWriter, WritesEveryFrameOnceInOrderWithTheEncodersBytes) {
  const auto dir = temp_dir("writer");
  const int w = 96, h = 54, frames = 9;
  std::vector<std::string> expected_names;
  {
    FrameWriter writer(dir, w, h, PngSettings{.level = 3}, 2);
    std::vector<std::uint8_t> pixels;
    for (int f = 0; f < frames; ++f) {
      pixels = test_picture(w, h, static_cast<unsigned>(f));
      EXPECT_EQ(writer.submit(pixels), frame_path(dir, static_cast<std::uint64_t>(f)));
      // submit() copied the pixels: scribbling over them now must not change frame f
      std::fill(pixels.begin(), pixels.end(), std::uint8_t{0xAB});
      expected_names.push_back(frame_path(dir, static_cast<std::uint64_t>(f)).filename());
    }
    EXPECT_EQ(writer.frames_submitted(), static_cast<std::uint64_t>(frames));
    writer.finish();
  }
  EXPECT_EQ(names_in(dir), expected_names);  // each exactly once, nothing else (no temporaries)
  PngEncoder reference(PngSettings{.level = 3});
  for (int f = 0; f < frames; ++f) {
    const auto picture = test_picture(w, h, static_cast<unsigned>(f));
    const auto bytes = read_all(frame_path(dir, static_cast<std::uint64_t>(f)));
    EXPECT_EQ(decode(bytes, w, h), picture) << "frame " << f;
    const auto png = reference.encode(w, h, picture);
    EXPECT_TRUE(std::equal(png.begin(), png.end(), bytes.begin(), bytes.end())) << "frame " << f;
  }
  std::filesystem::remove_all(dir);
}

TEST(FrameWriter, DestructorWritesWhatWasSubmitted) {
  const auto dir = temp_dir("writer_dtor");
  {
    FrameWriter writer(dir, 40, 30, {}, 3);
    for (unsigned f = 0; f < 5; ++f) writer.submit(test_picture(40, 30, f));
  }  // no finish(): the destructor still drains the queue
  EXPECT_EQ(names_in(dir).size(), 5u);
  EXPECT_EQ(decode(read_all(frame_path(dir, 4)), 40, 30), test_picture(40, 30, 4));
  std::filesystem::remove_all(dir);
}

// A capture of every 3rd frame names each file by its frame index, not by how many came before;
// submit() without an index continues after the last.
TEST(FrameWriter, EveryKthFrameIsNamedByItsFrameIndex) {
  const auto dir = temp_dir("writer_every");
  {
    FrameWriter writer(dir, 24, 16);
    for (std::uint64_t f = 0; f < 10; f += 3) {
      EXPECT_EQ(writer.submit(test_picture(24, 16, unsigned(f)), f), frame_path(dir, f));
    }
    EXPECT_EQ(writer.frames_submitted(), 4u);
    EXPECT_EQ(writer.next_frame(), 10u);
    EXPECT_EQ(writer.submit(test_picture(24, 16, 10)), frame_path(dir, 10));
    // Back to a name already written, or to an earlier one: refused, nothing queued.
    EXPECT_THROW(writer.submit(test_picture(24, 16, 0), 10), std::invalid_argument);
    EXPECT_THROW(writer.submit(test_picture(24, 16, 0), 4), std::invalid_argument);
    writer.finish();
  }
  EXPECT_EQ(names_in(dir),
            (std::vector<std::string>{"frame_000000.png", "frame_000003.png", "frame_000006.png",
                                      "frame_000009.png", "frame_000010.png"}));
  for (const std::uint64_t f : {0u, 3u, 6u, 9u, 10u}) {
    EXPECT_EQ(decode(read_all(frame_path(dir, f)), 24, 16), test_picture(24, 16, unsigned(f))) << f;
  }
  std::filesystem::remove_all(dir);
}

TEST(FrameWriter, WorkerErrorReachesTheCallerNamingTheFileAndKeepsEarlierFrames) {
  const auto dir = temp_dir("writer_fail");
  // A directory where frame 3 must go: the worker's rename onto it fails (EISDIR), even as
  // root (a read-only directory would not stop root).
  std::filesystem::create_directories(frame_path(dir, 3) / "occupied");
  const int w = 64, h = 36;
  FrameWriter writer(dir, w, h, {}, 2);
  std::string message;
  int submitted = 0;
  try {
    for (; submitted < 12; ++submitted) writer.submit(test_picture(w, h, 7));
    writer.finish();
  } catch (const CaptureError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find(frame_path(dir, 3).string()), std::string::npos) << message;
  EXPECT_NE(message.find("is a directory"), std::string::npos) << message;
  EXPECT_GE(submitted, 3);  // frames 0..2 were accepted before the failure could be seen
  for (std::uint64_t f = 0; f < 3; ++f) {
    EXPECT_EQ(decode(read_all(frame_path(dir, f)), w, h), test_picture(w, h, 7)) << f;
  }
  // Nothing after the failed frame, no temporaries: frames 0..2 and the blocking directory.
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"frame_000000.png", "frame_000001.png",
                                                     "frame_000002.png", "frame_000003.png"}));
  // The failure sticks: later calls report it too.
  EXPECT_THROW(writer.submit(test_picture(w, h, 7)), CaptureError);
  EXPECT_THROW(writer.finish(), CaptureError);
  std::filesystem::remove_all(dir);
}

TEST(FrameWriter, RefusesBadArguments) {
  const auto dir = temp_dir("writer_args");
  EXPECT_THROW(FrameWriter(dir, 8, 8, PngSettings{.level = 13}), std::invalid_argument);
  EXPECT_THROW(FrameWriter(dir, 0, 8), std::invalid_argument);
  EXPECT_THROW(FrameWriter(dir, 8, 8, {}, 0), std::invalid_argument);
  FrameWriter writer(dir, 8, 8);
  EXPECT_THROW(writer.submit(std::vector<std::uint8_t>(8 * 8 * 4 - 1)), std::invalid_argument);
  writer.finish();
  EXPECT_TRUE(names_in(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(Capture, FailedWriteLeavesNoFileAndSaysWhy) {
  const auto dir = temp_dir("fail");
  const auto missing = dir / "no_such_dir" / "frame.png";
  try {
    write_file_atomic(missing, std::string_view("x"));
    FAIL();
  } catch (const CaptureError& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the directory " + missing.parent_path().string() +
                                         " does not exist"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(missing));
  EXPECT_THROW(write_png(dir / "a.png", 2, 2, std::vector<std::uint8_t>(3)), CaptureError);
  std::filesystem::remove_all(dir);
}

TEST(Capture, UncommittedFileNeverAppearsAndOldVersionSurvives) {
  const auto dir = temp_dir("atomic");
  const auto file = dir / "data.csv";
  write_file_atomic(file, std::string_view("old\n"));
  {
    AtomicFile f(file);
    f.append("new, but abandoned\n");
  }  // destroyed without commit (an error path)
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "old");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
  std::filesystem::remove_all(dir);
}

TEST(Capture, OutputDirectoryChecks) {
  const auto dir = temp_dir("outdir");
  prepare_output_dir(dir / "a" / "b");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "a" / "b"));
  write_file_atomic(dir / "plain", std::string_view("x"));
  EXPECT_THROW(prepare_output_dir(dir / "plain"), CaptureError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fixstep
