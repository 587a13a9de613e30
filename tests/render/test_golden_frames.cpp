// Golden frames: frames of every shipped scene at fixed ticks, compared with the reference PNGs
// in tests/golden/frames/ within a stated tolerance.
//
// Tolerance: a pixel matches when each of R, G, B differs by at most 24 (of 255), and a frame
// matches when at most 0.2 % of its pixels do not. llvmpipe may round a blended edge pixel
// differently on another CPU or Mesa build; a moved body, a missing spring or a changed colour
// changes hundreds to thousands of pixels by far more.
//
// On a mismatch the test writes, beside the build's test binary in golden_failures/, the frame
// it drew (NAME.actual.png) and a diff image (NAME.diff.png: black where pixels match, the
// absolute difference amplified 4x elsewhere, red where a pixel is beyond the tolerance).
//
// To change the pictures on purpose, regenerate the references and commit them:
//   FIXSTEP_REFRESH_GOLDEN=1 build/ci/bin/test_golden_frames
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "fixstep/app/session.hpp"
#include "fixstep/capture/capture.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/render.hpp"
#include "fixstep/scene/scene.hpp"
#include "overlay_card.hpp"
#include "scene_session.hpp"
#include "shape_card.hpp"

namespace fixstep {
namespace {

constexpr int width = 640, height = 360;
constexpr int channel_tolerance = 24;
constexpr double pixel_fraction_tolerance = 0.002;
constexpr std::uint64_t golden_frame_numbers[] = {0, 30, 90};  // at 60 frames/s

const std::filesystem::path scenes_dir = FIXSTEP_SOURCE_DIR "/assets/scenes";
const std::filesystem::path test_scenes_dir = FIXSTEP_SOURCE_DIR "/tests/scenes";
const std::filesystem::path golden_dir = FIXSTEP_SOURCE_DIR "/tests/golden/frames";

bool refreshing() {
  const char* v = std::getenv("FIXSTEP_REFRESH_GOLDEN");
  return v && *v == '1';
}

/// The frames `fixstep render SCENE --size 640x360` writes as frame_NNNNNN.png for the golden
/// frame numbers (the same Session, virtual clock and drawing).
std::vector<std::vector<std::uint8_t>> render(const Scene& scene) {
  Session session = testing::scene_session(scene, width, height);
  const VirtualClock clock(60.0);
  std::vector<std::vector<std::uint8_t>> frames;
  for (std::uint64_t f = 0; f <= golden_frame_numbers[std::size(golden_frame_numbers) - 1]; ++f) {
    if (f > 0) session.advance(clock.frame_seconds());
    session.draw();
    if (std::find(std::begin(golden_frame_numbers), std::end(golden_frame_numbers), f) !=
        std::end(golden_frame_numbers)) {
      const auto p = session.renderer().pixels();
      frames.emplace_back(p.begin(), p.end());
    }
  }
  return frames;
}

std::vector<std::uint8_t> read_png(const std::filesystem::path& file) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(file.string().c_str(), &w, &h, &n, 4);
  if (!data) return {};
  std::vector<std::uint8_t> out;
  if (w == width && h == height) out.assign(data, data + std::size_t(w) * h * 4);
  stbi_image_free(data);
  return out;
}

struct Comparison {
  std::size_t beyond = 0;  ///< pixels with a channel beyond channel_tolerance
  int worst = 0;           ///< largest channel difference
  std::vector<std::uint8_t> diff;
};

Comparison compare(const std::vector<std::uint8_t>& actual,
                   const std::vector<std::uint8_t>& golden) {
  Comparison c;
  c.diff.assign(actual.size(), 0);
  for (std::size_t p = 0; p < actual.size(); p += 4) {
    int d = 0;
    for (int ch = 0; ch < 3; ++ch) {
      const int e = std::abs(int(actual[p + ch]) - int(golden[p + ch]));
      d = std::max(d, e);
      c.diff[p + ch] = static_cast<std::uint8_t>(std::min(255, 4 * e));
    }
    c.worst = std::max(c.worst, d);
    if (d > channel_tolerance) {
      ++c.beyond;
      c.diff[p] = 255, c.diff[p + 1] = 0, c.diff[p + 2] = 0;
    }
    c.diff[p + 3] = 255;
  }
  return c;
}

bool matches(const Comparison& c) {
  return double(c.beyond) <= pixel_fraction_tolerance * width * height;
}

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(scenes_dir)) {
    if (e.path().extension() == ".toml") files.push_back(e.path().stem().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(GoldenFrames, EveryShippedSceneMatchesItsReferenceFrames) {
  const auto failures = std::filesystem::current_path() / "golden_failures";
  std::size_t compared = 0;
  for (const std::string& name : shipped_scenes()) {
    const auto frames = render(load_scene(scenes_dir / (name + ".toml")));
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const std::string stem = fmt::format("{}_frame_{:06}", name, golden_frame_numbers[i]);
      const auto reference = golden_dir / (stem + ".png");
      if (refreshing()) {
        write_png(reference, width, height, frames[i]);
        continue;
      }
      const auto golden = read_png(reference);
      ASSERT_FALSE(golden.empty()) << reference << " is missing or not a " << width << "x" << height
                                   << " PNG; see the refresh command in this file";
      const Comparison c = compare(frames[i], golden);
      ++compared;
      if (!matches(c)) {
        std::filesystem::create_directories(failures);
        write_png(failures / (stem + ".actual.png"), width, height, frames[i]);
        write_png(failures / (stem + ".diff.png"), width, height, c.diff);
        ADD_FAILURE() << stem << ": " << c.beyond << " pixels differ by more than "
                      << channel_tolerance << " (largest difference " << c.worst << "); allowed "
                      << pixel_fraction_tolerance * width * height << ". See "
                      << (failures / (stem + ".diff.png")) << " and .actual.png";
      }
    }
  }
  if (refreshing()) GTEST_SKIP() << "rewrote the reference frames in " << golden_dir;
  EXPECT_EQ(compared, shipped_scenes().size() * std::size(golden_frame_numbers));
}

TEST(GoldenFrames, OneFlippedBitOfPhysicsFailsTheComparison) {
  // The tolerance must not hide a change in the physics: flip one bit of the first spring's
  // stiffness (mantissa bit 50: k = 15 N/m becomes 11.25 N/m) and frame 90 no longer matches.
  if (refreshing()) GTEST_SKIP();
  Scene scene = load_scene(scenes_dir / "default.toml");
  auto& k = scene.def.bodies[0].spring->stiffness;
  k = std::bit_cast<double>(std::bit_cast<std::uint64_t>(k) ^ (std::uint64_t{1} << 50));
  ASSERT_NE(k, 15.0);
  const auto frames = render(scene);
  const auto golden = read_png(golden_dir / "default_frame_000090.png");
  ASSERT_FALSE(golden.empty());
  const Comparison c = compare(frames.back(), golden);
  EXPECT_FALSE(matches(c)) << c.beyond << " pixels beyond the tolerance";
  // And the unchanged scene, drawn twice, is identical to the pixel.
  const auto a = render(load_scene(scenes_dir / "default.toml"));
  const auto b = render(load_scene(scenes_dir / "default.toml"));
  EXPECT_EQ(a, b);
}

/// Compares `frame` with the reference `stem`.png (or, refreshing, writes it); a mismatch leaves
/// the frame and the diff in golden_failures/.
void expect_matches_reference(const std::vector<std::uint8_t>& frame, const std::string& stem) {
  const auto reference = golden_dir / (stem + ".png");
  if (refreshing()) {
    write_png(reference, width, height, frame);
    return;
  }
  const auto golden = read_png(reference);
  ASSERT_FALSE(golden.empty()) << reference << " is missing; see the refresh command in this file";
  const Comparison c = compare(frame, golden);
  if (!matches(c)) {
    const auto failures = std::filesystem::current_path() / "golden_failures";
    std::filesystem::create_directories(failures);
    write_png(failures / (stem + ".actual.png"), width, height, frame);
    write_png(failures / (stem + ".diff.png"), width, height, c.diff);
    ADD_FAILURE() << stem << ": " << c.beyond << " pixels differ by more than " << channel_tolerance
                  << " (largest difference " << c.worst << ")";
  }
}

// Joints (tests/scenes/joints_drawn.toml: a hinged rod with limits, a rope, a slider on a rail
// with limits, a rigid distance joint, a car's wheels and a weld), with their limits as its
// [view] joints = "limits" asks at the golden frame numbers, and at the last one with the
// default marks only ("anchors"): the same bodies, without the arcs and ticks.
TEST(GoldenFrames, TheJointsSceneMatchesItsReferenceFrames) {
  Scene scene = load_scene(test_scenes_dir / "joints_drawn.toml");
  ASSERT_EQ(scene.view.joints, SceneJoints::limits);
  const auto frames = render(scene);
  for (std::size_t i = 0; i < frames.size(); ++i)
    expect_matches_reference(frames[i],
                             fmt::format("joints_drawn_frame_{:06}", golden_frame_numbers[i]));
  scene.view.joints = SceneJoints::anchors;
  const auto anchors = render(scene);
  EXPECT_NE(anchors.back(), frames.back());  // the limits drew something
  expect_matches_reference(anchors.back(),
                           fmt::format("joints_drawn_anchors_frame_{:06}",
                                       golden_frame_numbers[std::size(golden_frame_numbers) - 1]));
  scene.view.joints = SceneJoints::off;
  EXPECT_NE(render(scene).back(), anchors.back());  // the marks drew something
  if (refreshing()) GTEST_SKIP() << "rewrote the joints' reference frames in " << golden_dir;
}

// A game's overlay images (DrawList::image: world space, turned, and screen space) over frame 90
// of the sprites scene (assets/scenes/sprites.toml, whose own frames are shipped scenes'),
// which the frame draws all by GL.
TEST(GoldenFrames, OverlayImagesOverTheSpritesSceneMatchTheirReferenceFrame) {
  const Scene scene = load_scene(scenes_dir / "sprites.toml");
  ASSERT_TRUE(scene.view.background_image);
  Session session = testing::scene_session(scene, width, height);
  const VirtualClock clock(60.0);
  const std::string crate = (scenes_dir / "sprites" / "crate.png").string();
  const std::string ball = (scenes_dir / "sprites" / "ball.png").string();
  DrawList overlay;
  overlay.image(crate, {3.0, 5.0}, {1.2, 0.6}, 0.5);                     // world, turned
  overlay.image(ball, {560.0, 60.0}, {64.0, 64.0}, 0.0, Space::screen);  // px
  overlay.image(crate, {400.0, 60.0}, {48.0, 48.0}, 0.8, Space::screen);
  std::vector<std::uint8_t> without;
  for (std::uint64_t f = 0; f <= 90; ++f) {
    if (f > 0) session.advance(clock.frame_seconds());
    session.draw();
  }
  without.assign(session.renderer().pixels().begin(), session.renderer().pixels().end());
  session.draw(overlay);
  const auto p = session.renderer().pixels();
  const std::vector<std::uint8_t> with_overlay(p.begin(), p.end());
  EXPECT_NE(with_overlay, without);  // the images drew something
  expect_matches_reference(with_overlay, "sprites_overlay_frame_000090");
  if (refreshing()) GTEST_SKIP() << "rewrote " << golden_dir << "/sprites_overlay_frame_000090.png";
}

// The overlay test card (web/overlay_card.hpp: every DrawList shape in world and screen
// coordinates, a view style of its own, the HUD bottom right) over default.toml at frame 60, as
// the page draws it with frames=61&overlay=card (the browser checks compare the two).
std::vector<std::uint8_t> render_overlay_card() {
  const Scene scene = load_scene(scenes_dir / "default.toml");
  SessionSettings settings{.width = width,
                           .height = height,
                           .title = "default.toml",
                           .view_center = scene.view.center,
                           .view_width = scene.view.width};
  web::overlay_card_style(settings);
  Session session(scene.def, settings);
  const VirtualClock clock(60.0);
  DrawList card;
  for (int f = 0; f <= 60; ++f) {
    if (f > 0) session.advance(clock.frame_seconds());
    web::overlay_card(card, session.view().center, session.view().width / 6.0);
    session.draw(card);
  }
  const auto p = session.renderer().pixels();
  return {p.begin(), p.end()};
}

TEST(GoldenFrames, TheOverlayCardMatchesItsReferenceFrame) {
  const std::string stem = "overlay_card_frame_000060";
  const auto frame = render_overlay_card();
  const auto reference = golden_dir / (stem + ".png");
  if (refreshing()) {
    write_png(reference, width, height, frame);
    GTEST_SKIP() << "rewrote " << reference;
  }
  const auto golden = read_png(reference);
  ASSERT_FALSE(golden.empty()) << reference << " is missing; see the refresh command in this file";
  const Comparison c = compare(frame, golden);
  if (!matches(c)) {
    const auto failures = std::filesystem::current_path() / "golden_failures";
    std::filesystem::create_directories(failures);
    write_png(failures / (stem + ".actual.png"), width, height, frame);
    write_png(failures / (stem + ".diff.png"), width, height, c.diff);
    ADD_FAILURE() << stem << ": " << c.beyond << " pixels differ by more than " << channel_tolerance
                  << " (largest difference " << c.worst << ")";
  }
}

// Bodies with shapes (tests/render/shape_card.hpp: boxes, capsules, a circle, a rounded
// pentagon, a sharp triangle, a body of two shapes, one asleep, beside discs and a spring),
// drawn from a hand-filled RenderFrame until a shipped scene has shapes.
TEST(GoldenFrames, TheShapesCardMatchesItsReferenceFrame) {
  const std::string stem = "shapes_card_frame";
  Renderer r(width, height);
  r.set_camera(Camera{.center = {0, 1}, .width = 16.0});
  r.draw(testing::shape_card_frame(), {});
  const std::vector<std::uint8_t> frame(r.pixels().begin(), r.pixels().end());
  const auto reference = golden_dir / (stem + ".png");
  if (refreshing()) {
    write_png(reference, width, height, frame);
    GTEST_SKIP() << "rewrote " << reference;
  }
  const auto golden = read_png(reference);
  ASSERT_FALSE(golden.empty()) << reference << " is missing; see the refresh command in this file";
  const Comparison c = compare(frame, golden);
  if (!matches(c)) {
    const auto failures = std::filesystem::current_path() / "golden_failures";
    std::filesystem::create_directories(failures);
    write_png(failures / (stem + ".actual.png"), width, height, frame);
    write_png(failures / (stem + ".diff.png"), width, height, c.diff);
    ADD_FAILURE() << stem << ": " << c.beyond << " pixels differ by more than " << channel_tolerance
                  << " (largest difference " << c.worst << ")";
  }
}

}  // namespace
}  // namespace fixstep
