#pragma once
/// @file
/// An 8-bit RGB picture and PNG output.

#include <filesystem>
#include <string>
#include <vector>

namespace clothcd::render {

/// An RGB image, row-major from the top-left, 3 bytes per pixel.
struct Image {
  int width = 0;                     ///< Pixels per row.
  int height = 0;                    ///< Rows.
  std::vector<unsigned char> rgb;    ///< width * height * 3 bytes.

  /// A `width` x `height` image filled with colour (r, g, b). Throws std::invalid_argument unless both sizes are > 0.
  Image(int width, int height, unsigned char r = 255, unsigned char g = 255, unsigned char b = 255);
  Image() = default;
};

/// Writes `image` as a PNG file. Throws std::runtime_error naming the path when writing fails or the image is empty.
void write_png(const Image& image, const std::filesystem::path& path);

/// Places `images` on a grid of `columns` columns (cells as large as the largest image, `gap` pixels apart, white
/// background) and returns the sheet; `labels[k]`, when given, is written in the top-left corner of image k (digits,
/// spaces and the letters of "STEP", in a small pixel font). Throws std::invalid_argument if `images` is empty,
/// `columns` < 1, or a label has another character.
[[nodiscard]] Image contact_sheet(const std::vector<Image>& images, int columns, int gap = 4,
                                  const std::vector<std::string>& labels = {});

}  // namespace clothcd::render
