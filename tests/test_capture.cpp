// PNG capture and atomic files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "fixstep/capture.hpp"

namespace fixstep {
namespace {

std::filesystem::path temp_dir(const char* name) {
  auto d = std::filesystem::temp_directory_path() / ("fixstep_test_" + std::string(name) + "_" +
                                                      std::to_string(::getpid()));
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

TEST(Capture, FailedWriteLeavesNoFileAndSaysWhy) {
  const auto dir = temp_dir("fail");
  const auto missing = dir / "no_such_dir" / "frame.png";
  try {
    write_file_atomic(missing, std::string_view("x"));
    FAIL();
  } catch (const CaptureError& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
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
