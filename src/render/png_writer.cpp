// PNG output through stb_image_write (public domain, Debian libstb-dev). Its implementation is compiled here, static to
// this file, so no other translation unit or library can clash with it.
#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <string>

#include "clothcd/render/image.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#if __has_include(<stb/stb_image_write.h>)
#include <stb/stb_image_write.h>
#else
#include <stb_image_write.h>
#endif

namespace clothcd::render {

Image::Image(int width_, int height_, unsigned char r, unsigned char g, unsigned char b) : width(width_), height(height_) {
  if (width_ <= 0 || height_ <= 0) throw std::invalid_argument("image sizes must be positive");
  rgb.resize(static_cast<size_t>(width_) * height_ * 3);
  for (size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = r;
    rgb[i + 1] = g;
    rgb[i + 2] = b;
  }
}

void write_png(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != static_cast<size_t>(image.width) * image.height * 3) {
    throw std::runtime_error(path.string() + ": cannot write an empty or malformed image");
  }
  // Encoded in memory and written here, so that a failed write (a full disk) is an error: stb's own file writer
  // reports only a failure to open the file.
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  auto append = [](void* context, void* data, int size) {
    static_cast<std::ofstream*>(context)->write(static_cast<const char*>(data), size);
  };
  if (stbi_write_png_to_func(append, &out, image.width, image.height, 3, image.rgb.data(), image.width * 3) == 0) {
    throw std::runtime_error(path.string() + ": cannot encode PNG");
  }
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

namespace {

// Rows of 3 pixels, top to bottom (bit 4: left column), for "0123456789" and "STEP ".
constexpr unsigned char kDigitGlyphs[10][5] = {{7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7},
                                               {5, 5, 7, 1, 1}, {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1},
                                               {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};

const unsigned char* glyph(char c) {
  static constexpr unsigned char kS[5] = {3, 4, 2, 1, 6}, kT[5] = {7, 2, 2, 2, 2}, kE[5] = {7, 4, 6, 4, 7},
                                 kP[5] = {6, 5, 6, 4, 4}, kSpace[5] = {0, 0, 0, 0, 0};
  if (c >= '0' && c <= '9') return kDigitGlyphs[c - '0'];
  switch (c) {
    case 'S':
      return kS;
    case 'T':
      return kT;
    case 'E':
      return kE;
    case 'P':
      return kP;
    case ' ':
      return kSpace;
    default:
      throw std::invalid_argument(std::string("contact sheet: no glyph for '") + c + "'");
  }
}

// Black text on a white box at (x, y), `scale` pixels per font pixel.
void draw_label(Image& image, int x, int y, const std::string& text, int scale) {
  const int width = static_cast<int>(text.size()) * 4 * scale + scale, height = 7 * scale;
  const auto paint = [&](int px, int py, unsigned char value) {
    if (px < 0 || py < 0 || px >= image.width || py >= image.height) return;
    unsigned char* p = &image.rgb[(static_cast<size_t>(py) * image.width + px) * 3];
    p[0] = p[1] = p[2] = value;
  };
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) paint(x + px, y + py, 255);
  for (std::size_t k = 0; k < text.size(); ++k) {
    const unsigned char* rows = glyph(text[k]);
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (rows[row] & (4 >> col))
          for (int a = 0; a < scale; ++a)
            for (int b = 0; b < scale; ++b)
              paint(x + scale + (static_cast<int>(k) * 4 + col) * scale + a, y + scale + row * scale + b, 0);
  }
}

}  // namespace

Image contact_sheet(const std::vector<Image>& images, int columns, int gap, const std::vector<std::string>& labels) {
  if (images.empty()) throw std::invalid_argument("contact sheet: no image");
  if (columns < 1) throw std::invalid_argument("contact sheet: columns must be >= 1");
  int cell_w = 0, cell_h = 0;
  for (const Image& im : images) {
    cell_w = std::max(cell_w, im.width);
    cell_h = std::max(cell_h, im.height);
  }
  const int n = static_cast<int>(images.size());
  const int cols = std::min(columns, n), rows = (n + cols - 1) / cols;
  Image sheet(cols * cell_w + (cols + 1) * gap, rows * cell_h + (rows + 1) * gap);
  for (int k = 0; k < n; ++k) {
    const Image& im = images[k];
    const int x0 = gap + (k % cols) * (cell_w + gap), y0 = gap + (k / cols) * (cell_h + gap);
    for (int y = 0; y < im.height; ++y) {
      std::copy_n(&im.rgb[static_cast<size_t>(y) * im.width * 3], static_cast<size_t>(im.width) * 3,
                  &sheet.rgb[(static_cast<size_t>(y0 + y) * sheet.width + x0) * 3]);
    }
    if (k < static_cast<int>(labels.size())) draw_label(sheet, x0 + 4, y0 + 4, labels[k], 2);
  }
  return sheet;
}

}  // namespace clothcd::render
