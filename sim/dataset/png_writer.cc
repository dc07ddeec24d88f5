#include "sim/dataset/png_writer.h"

#include <png.h>
#include <zlib.h>

#include "common/error.h"

namespace depot::sim {
namespace {

void append(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}
void no_flush(png_structp) {}
[[noreturn]] void on_error(png_structp, png_const_charp message) {
  throw Error(std::string("PNG encoding: ") + message);
}
void on_warning(png_structp, png_const_charp) {}

}  // namespace

std::vector<unsigned char> encode_png(const cv::Mat& image, PngKind kind, int level) {
  const bool color = image.type() == CV_8UC3;
  if (!color && image.type() != CV_16UC1 && image.type() != CV_8UC1)
    throw Error("PNG encoding: unsupported image type");
  std::vector<unsigned char> out;
  out.reserve(image.total() * image.elemSize() / 2 + 1024);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, nullptr);
    throw Error("PNG encoding: out of memory");
  }
  try {
    png_set_write_fn(png, &out, append, no_flush);
    const int bit_depth = image.depth() == CV_16U ? 16 : 8;
    png_set_IHDR(png, info, image.cols, image.rows, bit_depth,
                 color ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_filter(png, PNG_FILTER_TYPE_BASE,
                   kind == PngKind::kColor ? PNG_FILTER_SUB : PNG_FILTER_NONE);
    png_set_compression_level(png, level);
    png_set_compression_strategy(png,
                                 kind == PngKind::kColor ? Z_HUFFMAN_ONLY : Z_DEFAULT_STRATEGY);
    png_write_info(png, info);
    if (color) png_set_bgr(png);
    if (bit_depth == 16) png_set_swap(png);  // PNG is big-endian
    for (int y = 0; y < image.rows; ++y)
      png_write_row(png, const_cast<png_bytep>(image.ptr<png_byte>(y)));
    png_write_end(png, info);
  } catch (...) {
    png_destroy_write_struct(&png, &info);
    throw;
  }
  png_destroy_write_struct(&png, &info);
  return out;
}

}  // namespace depot::sim
