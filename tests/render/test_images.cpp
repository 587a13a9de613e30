// Images in the renderer (fixstep/render/image.hpp, Renderer::image, sprites, the tiled
// background, DrawList::image): decoded exactly, refused with the file named, drawn texel for
// texel (nearest, top row up), turned with their body, anchored to the world.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/image.hpp"
#include "fixstep/render/render.hpp"
#include "pixels.hpp"
#include "png_bytes.hpp"

namespace fixstep {
namespace render_images_test {  // named: a unity batch shares anonymous namespaces

using testing::at;
using testing::Rgb;

const std::filesystem::path sprites = FIXSTEP_SOURCE_DIR "/assets/scenes/sprites";

/// A scratch folder of its own, removed at the end.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("fixstep_images_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
};

/// A 4 x 3 image whose every texel is distinct: (16 x, 16 y + 8, 200, 255).
std::vector<std::uint8_t> numbered() {
  std::vector<std::uint8_t> rgba;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      for (const int v : {16 * x, 16 * y + 8, 200, 255}) rgba.push_back(std::uint8_t(v));
  return rgba;
}

std::string message(const std::function<void()>& f) {
  try {
    f();
  } catch (const ImageError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(Images, DecodesTheCommittedSpriteExactly) {
  const Image im = load_png((sprites / "crate.png").string());
  ASSERT_EQ(im.width, 16);
  ASSERT_EQ(im.height, 16);
  auto px = [&](int x, int y) {
    const std::size_t i = (std::size_t(y) * 16 + std::size_t(x)) * 4;
    return std::vector<int>{im.rgba[i], im.rgba[i + 1], im.rgba[i + 2], im.rgba[i + 3]};
  };
  EXPECT_EQ(px(0, 0), (std::vector<int>{250, 240, 200, 255}));  // the top-left corner
  EXPECT_EQ(px(15, 8), (std::vector<int>{70, 40, 20, 255}));    // the frame
  EXPECT_EQ(px(6, 9), (std::vector<int>{110, 70, 35, 255}));    // the brace (x == 15 - y)
  const Image ball = load_png((sprites / "ball.png").string());
  EXPECT_EQ(ball.rgba[3], 0);  // transparent outside the disc
}

TEST(Images, RefusesWhatIsNotAWholePngNamingTheFile) {
  const std::vector<std::uint8_t> good = testing::png_bytes(4, 3, numbered());
  EXPECT_EQ(decode_png(good, "n.png").rgba, numbered());
  const std::vector<std::uint8_t> jpeg = {0xff, 0xd8, 0xff, 0xe0, 0, 16, 'J', 'F', 'I', 'F'};
  EXPECT_EQ(message([&] { (void)decode_png(jpeg, "photo.jpg"); }),
            "image photo.jpg: not a PNG file (it does not start with the PNG signature)");
  const std::vector<std::uint8_t> cut(good.begin(), good.begin() + 40);
  EXPECT_EQ(message([&] { (void)decode_png(cut, "cut.png"); }).rfind("image cut.png: corrupt", 0),
            0u);
  const std::vector<std::uint8_t> wide = testing::png_bytes(1, 1, {}, max_image_side + 1, 1);
  EXPECT_EQ(message([&] { (void)decode_png(wide, "wide.png"); }),
            "image wide.png: 4097 x 1 px: an image is at most 4096 px a side");
  EXPECT_EQ(message([&] { (void)load_png("no/such.png"); }),
            "image no/such.png: cannot open it (No such file or directory)");
}

TEST(Images, TheCacheLoadsEachPathOnceAndStopsAtItsCount) {
  TempDir dir;
  const std::string a = (dir.path / "a.png").string();
  testing::write_bytes(a, testing::png_bytes(4, 3, numbered()));
  ImageCache cache;
  EXPECT_EQ(cache.index(a), 0u);
  std::filesystem::remove(a);
  EXPECT_EQ(cache.index(a), 0u);  // kept: not read again
  EXPECT_EQ(cache.bytes(), 48u);
  const std::vector<std::uint8_t> tiny = testing::png_bytes(1, 1);
  for (std::size_t i = 1; i < max_images; ++i) {
    const std::string f = (dir.path / (std::to_string(i) + ".png")).string();
    testing::write_bytes(f, tiny);
    ASSERT_EQ(cache.index(f), i);
  }
  const std::string last = (dir.path / "last.png").string();
  testing::write_bytes(last, tiny);
  EXPECT_EQ(message([&] { (void)cache.index(last); }), "image " + last + ": more than 256 images");
  EXPECT_EQ(cache.size(), max_images);
}

const ViewStyle plain{.grid = false, .axes = false, .scale_bar = false};

TEST(Images, EachPixelTakesTheTexelUnderItsCentreTopRowUp) {
  // 4 x 3 texels over a 32 x 24 px rectangle from (10, 20): 8 x 8 px a texel, exactly.
  TempDir dir;
  const std::string file = (dir.path / "n.png").string();
  testing::write_bytes(file, testing::png_bytes(4, 3, numbered()));
  Renderer r(64, 64);
  r.begin({0, 0, 0, 255});
  const Renderer::Point corners[4] = {{10, 20}, {42, 20}, {42, 44}, {10, 44}};
  r.image(file, corners);
  r.finish();
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool inside = x >= 10 && x < 42 && y >= 20 && y < 44;
      const int tx = (x - 10) / 8, ty = (y - 20) / 8;
      const Rgb want = inside ? Rgb{16 * tx, 16 * ty + 8, 200} : Rgb{0, 0, 0};
      const Rgb got = at(r, x, y);
      ASSERT_TRUE(got.r == want.r && got.g == want.g && got.b == want.b)
          << "pixel " << x << ", " << y << ": " << got.r << " " << got.g << " " << got.b;
    }
  }
}

/// A frame of one body at the origin drawn as crate.png, 2 x 2 m, turned by `angle`, on a
/// 200 x 200 px view 5 m wide (40 px per m, the body's centre at pixel corner (100, 100)).
std::vector<std::uint8_t> crate_frame(float angle,
                                      std::vector<std::uint8_t>* out_pixels = nullptr) {
  RenderFrame f;
  f.x = {0.0f};
  f.y = {0.0f};
  f.ids = {Entity{1, 1}};
  f.radius = {1.0f};
  f.color = {Rgba8{255, 0, 0, 255}};
  f.angle = {angle};
  f.sprites.push_back({.body = 0,
                       .cx = 0,
                       .cy = 0,
                       .width = 2,
                       .height = 2,
                       .path = (sprites / "crate.png").string()});
  Renderer r(200, 200);
  r.set_camera(Camera{.center = {0, 0}, .width = 5.0});
  r.set_view_style(plain);
  r.draw(f, {});
  std::vector<std::uint8_t> p(r.pixels().begin(), r.pixels().end());
  if (out_pixels) *out_pixels = p;
  return p;
}

Rgb pixel(const std::vector<std::uint8_t>& p, int x, int y) {
  const std::size_t i = (std::size_t(y) * 200 + std::size_t(x)) * 4;
  return {p[i], p[i + 1], p[i + 2]};
}

TEST(Images, ASpriteReplacesItsBodysDiscAndTurnsWithIt) {
  // The crate's top-left 4 x 4 texels (250, 240, 200) cover [-1, -0.5] x [0.5, 1] m unturned:
  // pixels 60..79 across, 60..79 down. Turned a quarter counter-clockwise they cover
  // [-1, -0.5] x [-1, -0.5] m: rows 120..139.
  const std::vector<std::uint8_t> flat = crate_frame(0.0f);
  const std::vector<std::uint8_t> turned = crate_frame(float(std::numbers::pi / 2));
  auto corner = [](Rgb p) { return p.r == 250 && p.g == 240 && p.b == 200; };
  EXPECT_TRUE(corner(pixel(flat, 65, 65)));
  EXPECT_FALSE(corner(pixel(flat, 65, 134)));
  EXPECT_TRUE(corner(pixel(turned, 65, 134)));
  EXPECT_FALSE(corner(pixel(turned, 65, 65)));
  // No red disc anywhere: the sprite is drawn instead.
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x)
      ASSERT_FALSE(pixel(flat, x, y).r == 255 && pixel(flat, x, y).g == 0);
}

TEST(Images, TheBackgroundIsAnchoredToTheWorld) {
  // tiles.png every 1.5 m: a camera moved by a whole tile draws the same frame, by half a tile
  // another.
  auto frame = [](double cx) {
    Renderer r(120, 80);
    ViewStyle style = plain;
    style.background_image = (sprites / "tiles.png").string();
    style.background_tile = 1.5;
    r.set_view_style(style);
    r.set_camera(Camera{.center = {cx, 0.25}, .width = 12.0});  // 10 px per m
    RenderFrame f;
    r.draw(f, {});
    return std::vector<std::uint8_t>(r.pixels().begin(), r.pixels().end());
  };
  const auto a = frame(0.0);
  EXPECT_EQ(a, frame(1.5));
  EXPECT_EQ(a, frame(-3.0));
  EXPECT_NE(a, frame(0.75));
}

TEST(Images, AnOverlayImageIsDrawnInWorldAndScreenSpace) {
  // The same 2 x 2 m crate as a sprite and as a world image, and as a screen image of 80 px.
  std::vector<std::uint8_t> sprite;
  (void)crate_frame(0.0f, &sprite);
  auto overlay_frame = [](const DrawList& list) {
    Renderer r(200, 200);
    r.set_camera(Camera{.center = {0, 0}, .width = 5.0});
    r.set_view_style(plain);
    r.draw_scene(RenderFrame{});
    list.draw(r);
    r.finish();
    return std::vector<std::uint8_t>(r.pixels().begin(), r.pixels().end());
  };
  DrawList world, screen;
  world.image((sprites / "crate.png").string(), {0, 0}, {2, 2});
  screen.image((sprites / "crate.png").string(), {100, 100}, {80, 80}, 0.0, Space::screen);
  EXPECT_EQ(overlay_frame(world), sprite);
  EXPECT_EQ(overlay_frame(screen), sprite);
  DrawList bad;
  bad.image("no/such.png", {0, 0}, {1, 1});
  EXPECT_THROW(overlay_frame(bad), ImageError);
  EXPECT_THROW(bad.image("x.png", {0, 0}, {-1, 1}), std::invalid_argument);
}

}  // namespace render_images_test
}  // namespace fixstep
