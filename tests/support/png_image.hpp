#pragma once
/// @file
/// A PNG decoded to RGBA with libpng's simplified API, and where a colour is in it.

#include <png.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagrange::testing {

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;  ///< row-major RGBA
};

inline RgbaImage decodePng(const std::string& bytes) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw std::runtime_error(std::string("not a PNG: ") + image.message);
  image.format = PNG_FORMAT_RGBA;
  RgbaImage out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.pixels.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr))
    throw std::runtime_error(std::string("cannot decode the PNG: ") + image.message);
  return out;
}

struct ColourBlob {
  long count = 0;
  double x = 0.0, y = 0.0;  ///< centroid [px]
};

/// The pixels within `tolerance` of (r, g, b) in every channel, in the
/// rectangle [x0, x1) x [y0, y1): how many and their centroid.
inline ColourBlob findColour(const RgbaImage& image, int r, int g, int b, int tolerance, int x0, int y0,
                             int x1, int y1) {
  ColourBlob blob;
  for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y)
    for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x) {
      const unsigned char* p = &image.pixels[4 * (static_cast<size_t>(y) * image.width + x)];
      if (std::abs(p[0] - r) <= tolerance && std::abs(p[1] - g) <= tolerance &&
          std::abs(p[2] - b) <= tolerance) {
        ++blob.count;
        blob.x += x + 0.5;
        blob.y += y + 0.5;
      }
    }
  if (blob.count > 0) {
    blob.x /= blob.count;
    blob.y /= blob.count;
  }
  return blob;
}

}  // namespace lagrange::testing
