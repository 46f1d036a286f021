// PNG encoding through libpng, written atomically.
#include "sfit/render/image.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "sfit/error.h"
#include "test_support.h"

namespace sfit::test {
namespace {

render::Image pattern(int w, int h) {
  render::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.set(x, y,
              {static_cast<std::uint8_t>(x * 7), static_cast<std::uint8_t>(y * 13),
               static_cast<std::uint8_t>((x ^ y) * 3)});
  return img;
}

TEST(Image, PngRoundTripsEveryPixel) {
  const std::string dir = temp_dir();
  const render::Image img = pattern(37, 23);
  render::write_png(dir + "/a.png", img);
  const render::Image back = render::read_png(dir + "/a.png");
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 23);
  EXPECT_EQ(back.rgb, img.rgb);
  // The temporary file was renamed: only a.png is left.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
  const std::string bytes = read_file(dir + "/a.png");
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
}

TEST(Image, OverwritesAnExistingPictureWhole) {
  const std::string dir = temp_dir();
  render::write_png(dir + "/a.png", pattern(64, 64));
  render::write_png(dir + "/a.png", pattern(8, 4));
  EXPECT_EQ(render::read_png(dir + "/a.png").width, 8);
}

TEST(Image, MissingFolderIsAnOutputError) {
  try {
    render::write_png(temp_dir() + "/no/such/folder/a.png", pattern(4, 4));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutputWrite);
    EXPECT_NE(e.place().file.find("a.png"), std::string::npos);
  }
}

TEST(Image, ReadingChecksTheFile) {
  const std::string dir = temp_dir();
  try {
    render::read_png(dir + "/missing.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputUnreadable);
  }
  write_file(dir + "/text.png", "not a png at all");
  try {
    render::read_png(dir + "/text.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInputSyntax);
  }
}

TEST(Image, EncodingRefusesAnInconsistentBuffer) {
  render::Image img = pattern(4, 4);
  img.rgb.pop_back();
  EXPECT_THROW(render::encode_png(img), Error);
}

}  // namespace
}  // namespace sfit::test
