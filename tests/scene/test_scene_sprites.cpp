// Sprites and styled levels in scene files (scene_images.cpp): a body's sprite and sprite_size,
// a shape's colour, a segment's and polyline's colour and width, [view] background_image and
// background_tile; paths resolved against the scene file's folder; drawing only (the definition
// and state hashes are those of the scene without them); the writer's exact round trip; each bad
// image refused at its file:line:column and key, naming the file (io's check_png).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/io/png_check.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "png_bytes.hpp"
#include "scene_writer_check.hpp"

namespace fixstep {
namespace scene_sprites_test {  // named: a unity batch shares anonymous namespaces

const std::filesystem::path dir = FIXSTEP_SOURCE_DIR "/assets/scenes";

std::string error_of(const std::string& text, const std::string& name) {
  try {
    (void)parse_scene(text, name);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneSprites, TheKeysAreReadAndPathsResolvedAgainstTheScenesFolder) {
  const Scene s = load_scene(dir / "sprites.toml");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const std::string folder = dir.string();
  ASSERT_TRUE(s.view.background_image);
  EXPECT_EQ(*s.view.background_image, folder + "/sprites/tiles.png");
  EXPECT_EQ(s.view.background_tile, 1.5);
  const BodyDef& crate = s.def.bodies[0];
  EXPECT_EQ(crate.appearance->sprite, folder + "/sprites/crate.png");
  EXPECT_EQ(crate.appearance->sprite_size.x, 0.0);  // the shapes' bounds
  const BodyDef& ball = s.def.bodies[1];
  EXPECT_EQ(ball.appearance->sprite, folder + "/sprites/ball.png");
  EXPECT_EQ(ball.appearance->sprite_size.x, 0.8);
  EXPECT_EQ(ball.appearance->sprite_size.y, 0.8);
  const BodyDef& hammer = s.def.bodies[2];
  EXPECT_EQ(hammer.shapes[0].color, (Rgba8{0xdc, 0xdc, 0xdc, 255}));
  EXPECT_EQ(hammer.shapes[1].color, (Rgba8{0x4c, 0x6e, 0xf5, 255}));
  EXPECT_FALSE(hammer.appearance);       // no drawing key on the body itself
  ASSERT_EQ(s.def.segments.size(), 4u);  // the ledge, then the floor's three
  EXPECT_EQ(s.def.segments[0].color, (Rgba8{0xc8, 0xa0, 0x64, 0x80}));
  EXPECT_EQ(s.def.segments[0].width, 0.12);
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_EQ(s.def.segments[i].color, (Rgba8{0x6f, 0xbf, 0x73, 255})) << i;
    EXPECT_EQ(s.def.segments[i].width, 0.2) << i;
  }
}

/// The sprites scene with every drawing key of this file's taken out.
std::string without_looks(std::string text) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end - at);
    at = end == std::string::npos ? text.size() : end + 1;
    bool looks = false;
    for (const char* key : {"sprite", "background_", "color", "width = 0."}) {
      looks = looks || line.rfind(key, 0) == 0;
    }
    if (!looks) out += line + "\n";
  }
  return out;
}

TEST(SceneSprites, DrawingOnlyTheHashesAreTheSceneWithoutThem) {
  const Scene s = load_scene(dir / "sprites.toml");
  const std::string plain_text = without_looks(s.text);
  ASSERT_EQ(plain_text.find("\nsprite"), std::string::npos);
  ASSERT_NE(plain_text.find("width = 12.0"), std::string::npos);  // the view's width stays
  const Scene plain = parse_scene(plain_text, (dir / "plain.toml").string());
  EXPECT_EQ(definition_hash(s.def), definition_hash(plain.def));
  World a(s.def), b(plain.def);
  for (int t = 0; t < 120; ++t) a.step(), b.step();
  EXPECT_EQ(a.state_hash(), b.state_hash());
}

TEST(SceneSprites, WriteSceneRoundTripsTheKeysBitForBit) {
  Scene s = load_scene(dir / "sprites.toml");
  s.def.bodies[1].appearance->sprite_size = {0.1 + 0.2, 1.0 / 3.0};  // every bit written
  const std::string text = format_scene(s.def);
  EXPECT_NE(text.find("sprite = \"" + (dir / "sprites" / "crate.png").string() + "\""),
            std::string::npos)
      << text;
  const Scene back = parse_scene(text, "<written>");
  test::expect_same_world(s.def, back.def);
  EXPECT_EQ(format_scene(back.def), text);
  // A size with a zero side draws as the default: not written, it reloads as {0, 0}.
  s.def.bodies[1].appearance->sprite_size = {0.5, 0.0};
  EXPECT_EQ(parse_scene(format_scene(s.def), "<written>").def.bodies[1].appearance->sprite_size.x,
            0.0);
}

const std::string world = "[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\n";

TEST(SceneSprites, BadImagesAreRefusedAtTheirKeyNamingTheFile) {
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path() / "fixstep_scene_sprites_test";
  std::filesystem::create_directories(tmp);
  const std::string scene = (tmp / "s.toml").string();
  std::vector<std::uint8_t> good = testing::png_bytes(2, 2);
  testing::write_bytes(tmp / "good.png", good);
  std::vector<std::uint8_t> bad = good;
  bad[40] ^= 1;  // inside IHDR... or IDAT: a CRC no longer matches
  testing::write_bytes(tmp / "crc.png", bad);
  testing::write_bytes(tmp / "cut.png", std::vector<std::uint8_t>(good.begin(), good.end() - 20));
  testing::write_bytes(tmp / "big.png", testing::png_bytes(1, 1, {}, 1, 4097));
  testing::write_bytes(tmp / "jpeg.png", {0xff, 0xd8, 0xff, 0xe0, 0, 0, 0, 0, 0, 0});
  const std::string at = scene + ":6:10: body[0].sprite: image " + (tmp / "").string();
  EXPECT_EQ(error_of(world + "sprite = \"good.png\"\n", scene), "(no error)");
  EXPECT_EQ(error_of(world + "sprite = \"gone.png\"\n", scene), at + "gone.png: no such file");
  EXPECT_EQ(error_of(world + "sprite = \"jpeg.png\"\n", scene),
            at + "jpeg.png: not a PNG file (it does not start with the PNG signature)");
  EXPECT_EQ(
      error_of(world + "sprite = \"crc.png\"\n", scene).rfind(at + "crc.png: corrupt (chunk", 0),
      0u);
  EXPECT_EQ(error_of(world + "sprite = \"cut.png\"\n", scene).rfind(at + "cut.png: truncated", 0),
            0u);
  EXPECT_EQ(error_of(world + "sprite = \"big.png\"\n", scene),
            at + "big.png: 1 x 4097 px: an image is 1 to 4096 px a side");
  EXPECT_EQ(
      error_of(world + "sprite = \"\"\n", scene),
      scene + ":6:10: body[0].sprite: expected the path of a PNG file, found an empty string");
  EXPECT_EQ(error_of(world + "sprite_size = [1.0, 1.0]\n", scene),
            scene +
                ":6:15: body[0].sprite_size: needs a sprite: the size (m) of the image drawn "
                "for the body; add sprite = \"image.png\"");
  EXPECT_EQ(error_of("[world]\ndt = 0.01\n[view]\nbackground_image = \"jpeg.png\"\n" +
                         world.substr(std::string("[world]\ndt = 0.01\n").size()),
                     scene),
            scene + ":4:20: view.background_image: image " + (tmp / "jpeg.png").string() +
                ": not a PNG file (it does not start with the PNG signature)");
  EXPECT_EQ(error_of(world + "[[segment]]\na = [0.0, 0.0]\nb = [1.0, 0.0]\nwidth = 0.0\n", scene)
                .rfind(scene + ":9:9: segment[0].width: must be > 0 m", 0),
            0u);
  std::filesystem::remove_all(tmp);
}

TEST(SceneSprites, CheckPngReadsTheChunksWithoutDecoding) {
  const std::vector<std::uint8_t> good = testing::png_bytes(3, 2);
  const PngSize size = check_png(good);
  EXPECT_EQ(size.width, 3);
  EXPECT_EQ(size.height, 2);
  // Every byte changed after the signature breaks a CRC (or the structure): none passes.
  for (std::size_t i = 8; i < good.size(); ++i) {
    std::vector<std::uint8_t> bad = good;
    bad[i] ^= 0x10;
    EXPECT_THROW((void)check_png(bad), std::runtime_error) << "byte " << i;
  }
}

}  // namespace scene_sprites_test
}  // namespace fixstep
