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

Image contact_sheet(const std::vector<Image>& images, int columns, int gap) {
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
  }
  return sheet;
}

}  // namespace clothcd::render
