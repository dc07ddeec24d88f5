#include "common/png_codec.h"

#include <png.h>
#include <zlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <opencv2/imgcodecs.hpp>

#include "common/error.h"

namespace depot {
namespace {

void append(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}
void no_flush(png_structp) {}
[[noreturn]] void on_encode_error(png_structp, png_const_charp message) {
  throw Error(std::string("PNG encoding: ") + message);
}
// libpng's reason for giving up, thrown through its C frames (the x86-64 ABI
// keeps unwind tables in C code too) and caught in read_png.
struct PngReadError {
  std::string reason;
};
[[noreturn]] void on_decode_error(png_structp, png_const_charp message) {
  throw PngReadError{message};
}
void on_warning(png_structp, png_const_charp) {}

bool has_png_signature(std::FILE* file) {
  unsigned char signature[8] = {};
  const bool png = std::fread(signature, 1, 8, file) == 8 && png_sig_cmp(signature, 0, 8) == 0;
  std::rewind(file);
  return png;
}

cv::Mat read_png(const std::string& path, std::FILE* file, ImageRead mode) {
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, on_decode_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    fail(path, "out of memory reading PNG");
  }
  cv::Mat image;
  try {
    png_init_io(png, file);
    png_read_info(png, info);
    const int color_type = png_get_color_type(png, info);
    int bit_depth = png_get_bit_depth(png, info);
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (color_type & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
    const bool gray = color_type == PNG_COLOR_TYPE_GRAY || color_type == PNG_COLOR_TYPE_GRAY_ALPHA;
    if (mode == ImageRead::kColor) {
      if (bit_depth == 16) png_set_strip_16(png);
      if (gray) png_set_gray_to_rgb(png);
    }
    if (!gray || mode == ImageRead::kColor) png_set_bgr(png);
    if (bit_depth == 16 && mode == ImageRead::kUnchanged) png_set_swap(png);  // big-endian file
    png_read_update_info(png, info);
    bit_depth = png_get_bit_depth(png, info);
    const int channels = png_get_channels(png, info);
    const int width = static_cast<int>(png_get_image_width(png, info));
    const int height = static_cast<int>(png_get_image_height(png, info));
    image.create(height, width, CV_MAKETYPE(bit_depth == 16 ? CV_16U : CV_8U, channels));
    std::vector<png_bytep> rows(static_cast<size_t>(height));
    for (int y = 0; y < height; ++y) rows[y] = image.ptr<png_byte>(y);
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
  } catch (const PngReadError& e) {
    png_destroy_read_struct(&png, &info, nullptr);
    fail(path, "damaged PNG (" + e.reason + ")");
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

}  // namespace

std::vector<unsigned char> encode_png(const cv::Mat& image, PngKind kind, int level) {
  const bool color = image.type() == CV_8UC3;
  if (!color && image.type() != CV_16UC1 && image.type() != CV_8UC1)
    throw Error("PNG encoding: unsupported image type");
  std::vector<unsigned char> out;
  out.reserve(image.total() * image.elemSize() / 2 + 1024);
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, on_encode_error, on_warning);
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

cv::Mat read_image(const std::string& path, ImageRead mode) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "image missing");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
  if (!file) fail(path, "cannot open image");
  if (has_png_signature(file.get())) return read_png(path, file.get(), mode);
  file.reset();
  cv::Mat image =
      cv::imread(path, mode == ImageRead::kColor ? cv::IMREAD_COLOR : cv::IMREAD_UNCHANGED);
  if (image.empty()) fail(path, "unreadable image (not a PNG, and OpenCV cannot decode it)");
  return image;
}

size_t write_png(const std::string& path, const cv::Mat& image, PngKind kind,
                 int compression_level) {
  const std::vector<unsigned char> buf = encode_png(image, kind, compression_level);
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(buf.data()), static_cast<std::streamsize>(buf.size()));
  if (!out) fail(path, "write failed (disk full?)");
  return buf.size();
}

}  // namespace depot
