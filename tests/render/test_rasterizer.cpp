// The rasterizer and PNG writer: a rendered sphere has the right size, shows the object in front of the background,
// and reads back from PNG unchanged; contact sheets lay images out on a grid.
#include <catch2/catch.hpp>
#include <filesystem>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>

#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/render/rasterizer.hpp"

using namespace clothcd;
using namespace clothcd::render;

namespace {

long count_not_background(const Image& image, const RenderSettings& settings) {
  const Image blank(1, 1, static_cast<unsigned char>(settings.background.x() * 255 + 0.5),
                    static_cast<unsigned char>(settings.background.y() * 255 + 0.5),
                    static_cast<unsigned char>(settings.background.z() * 255 + 0.5));
  long count = 0;
  for (size_t i = 0; i < image.rgb.size(); i += 3) {
    count += image.rgb[i] != blank.rgb[0] || image.rgb[i + 1] != blank.rgb[1] || image.rgb[i + 2] != blank.rgb[2];
  }
  return count;
}

}  // namespace

TEST_CASE("a rendered sphere fills about its projected disc and round-trips through PNG", "[render]") {
  const TriangleMesh sphere = make_uv_sphere(0.5, 32, 16);
  RenderSettings settings;
  settings.width = 200;
  settings.height = 150;
  Camera camera;
  camera.eye = Eigen::Vector3d(0, 0, 3);
  camera.target = Eigen::Vector3d::Zero();
  const Image image = clothcd::render::render({{&sphere, {0.9, 0.4, 0.2}}}, camera, settings);
  REQUIRE(image.width == 200);
  REQUIRE(image.height == 150);
  // Projected radius: focal * r / sqrt(d^2 - r^2), focal = 75 / tan(20 deg).
  const double focal = 75.0 / std::tan(20.0 * M_PI / 180.0);
  const double radius = focal * 0.5 / std::sqrt(9.0 - 0.25);
  const double disc = M_PI * radius * radius;
  const long drawn = count_not_background(image, settings);
  CHECK(drawn > 0.9 * disc);
  CHECK(drawn < 1.1 * disc);
  // The corners stay background, the centre is drawn.
  CHECK(image.rgb[0] == static_cast<unsigned char>(settings.background.x() * 255 + 0.5));
  const size_t centre = (75 * 200 + 100) * 3;
  CHECK(image.rgb[centre] > image.rgb[centre + 2]);  // orange-ish: red above blue

  const auto path = std::filesystem::temp_directory_path() / "clothcd-render-test.png";
  write_png(image, path);
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &w, &h, &channels, 3);
  REQUIRE(data != nullptr);
  CHECK(w == 200);
  CHECK(h == 150);
  CHECK(std::equal(image.rgb.begin(), image.rgb.end(), data));
  stbi_image_free(data);
}

TEST_CASE("the nearer triangle wins the depth test", "[render]") {
  TriangleMesh near_quad = make_grid(2, 2, 1.0, 1.0), far_quad = make_grid(2, 2, 4.0, 4.0);
  far_quad.vertices.col(1).array() -= 1.0;
  Camera camera;
  camera.eye = Eigen::Vector3d(0, 3, 0.001);
  camera.target = Eigen::Vector3d::Zero();
  RenderSettings settings;
  settings.width = settings.height = 64;
  // Draw the near one first, then the far one: the centre must keep the near colour.
  const Image image = clothcd::render::render({{&near_quad, {1, 0, 0}}, {&far_quad, {0, 0, 1}}}, camera, settings);
  const size_t centre = (32 * 64 + 32) * 3;
  CHECK(image.rgb[centre] > 0);
  CHECK(image.rgb[centre + 2] == 0);
}

TEST_CASE("a contact sheet lays images on a grid, and bad input throws", "[render]") {
  const std::vector<Image> images(5, Image(30, 20, 0, 0, 0));
  const Image sheet = contact_sheet(images, 2, 4);
  CHECK(sheet.width == 2 * 30 + 3 * 4);
  CHECK(sheet.height == 3 * 20 + 4 * 4);
  CHECK(sheet.rgb[0] == 255);                                  // gap
  CHECK(sheet.rgb[(4 * sheet.width + 4) * 3] == 0);            // first image
  CHECK_THROWS(contact_sheet({}, 2));
  // Labels: black pixels of the font on a white box in the image's corner (the images are black), in the
  // top-left of each cell; a character the font lacks is an error.
  const Image labelled = contact_sheet(images, 2, 4, {"STEP 0", "STEP 12"});
  const auto white_at = [&](int x, int y) { return labelled.rgb[(static_cast<size_t>(y) * labelled.width + x) * 3] == 255; };
  // Image 0 starts at (4, 4), its label box at (8, 8); the glyphs at (10, 10), 2 pixels per font pixel. The top row
  // of 'S' is .XX: white at x 10-11, black at 12-15.
  CHECK(white_at(8, 8));
  CHECK(white_at(10, 10));
  CHECK_FALSE(white_at(12, 10));
  CHECK_FALSE(white_at(15, 11));
  CHECK(white_at(4 + 30 + 4 + 4, 8));  // image 1's label box
  CHECK_FALSE(white_at(9, 22));        // below the 14-pixel label box: the black image
  CHECK_THROWS(contact_sheet(images, 2, 4, {"step"}));
  CHECK_THROWS(Image(0, 10));
  CHECK_THROWS(write_png(Image(), std::filesystem::temp_directory_path() / "clothcd-empty.png"));
  CHECK_THROWS(write_png(Image(4, 4), "/nonexistent-dir/x.png"));
  if (std::filesystem::exists("/dev/full")) {  // opens, but every write fails (Linux): not a silent success
    CHECK_THROWS_WITH(write_png(Image(4, 4), "/dev/full"), Catch::Contains("write failed"));
  }
}
