#include "sfit/render/image.h"

#include <png.h>

#include <cstring>
#include <filesystem>
#include <ostream>

#include "sfit/error.h"
#include "sfit/io/atomic_file.h"

namespace sfit::render {

Image::Image(int w, int h, Rgb fill) : width(w), height(h) {
  rgb.resize(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = fill.r;
    rgb[i + 1] = fill.g;
    rgb[i + 2] = fill.b;
  }
}

// libpng's simplified API (1.6): no setjmp/longjmp crosses our C++ frames; failures come back
// as a zero return with the reason in png_image::message.
std::vector<std::uint8_t> encode_png(const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw Error(ErrorCode::kInternal, "encode_png: image size and pixel buffer disagree", Place{},
                {static_cast<double>(image.width), static_cast<double>(image.height)});
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  png_alloc_size_t bytes = 0;
  if (!png_image_write_to_memory(&png, nullptr, &bytes, 0, image.rgb.data(), 0, nullptr))
    throw Error(ErrorCode::kInternal, std::string("libpng: ") + png.message);
  std::vector<std::uint8_t> out(bytes);
  if (!png_image_write_to_memory(&png, out.data(), &bytes, 0, image.rgb.data(), 0, nullptr))
    throw Error(ErrorCode::kInternal, std::string("libpng: ") + png.message);
  out.resize(bytes);
  return out;
}

void write_png(const std::string& path, const Image& image) {
  const std::vector<std::uint8_t> bytes = encode_png(image);
  io::write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  });
}

Image read_png(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(ErrorCode::kInputUnreadable, "no such PNG file", Place{.file = path});
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw Error(ErrorCode::kInputSyntax, std::string("not a readable PNG: ") + png.message,
                Place{.file = path});
  png.format = PNG_FORMAT_RGB;
  Image img(static_cast<int>(png.width), static_cast<int>(png.height));
  const png_color white{255, 255, 255};
  if (!png_image_finish_read(&png, &white, img.rgb.data(), 0, nullptr)) {
    png_image_free(&png);
    throw Error(ErrorCode::kInputSyntax, std::string("PNG decoding failed: ") + png.message,
                Place{.file = path});
  }
  return img;
}

}  // namespace sfit::render
