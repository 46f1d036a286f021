// An 8-bit RGB picture and its PNG encoding (libpng), written atomically.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sfit::render {

/// An sRGB colour, 8 bits per channel.
struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

/// width x height pixels, row-major from the top-left corner, 3 bytes (R, G, B) a pixel.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(int w, int h, Rgb fill = {255, 255, 255});
  Rgb at(int x, int y) const {
    const std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
  }
  void set(int x, int y, Rgb c) {
    std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
};

/// The image as PNG file bytes. Throws Error(kInternal) if libpng fails.
std::vector<std::uint8_t> encode_png(const Image& image);

/// Writes the image as PNG to `path` through a temporary file renamed onto it
/// (io::write_file_atomically). Throws Error(kOutputWrite) naming the path.
void write_png(const std::string& path, const Image& image);

/// Reads a PNG file (any colour type, alpha composited on white) as 8-bit RGB; for tests and
/// tools. Throws Error(kInputUnreadable) if the file is missing and Error(kInputSyntax) if it is
/// not a PNG libpng can decode.
Image read_png(const std::string& path);

}  // namespace sfit::render
