#include "io/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/exr_memory_stream.h"

namespace brdfit {
namespace {
// Display values clamped to [0, 1] and quantized by round(255 v); non-finite -> 0.
std::vector<png_byte> Quantize(const Image& display) {
  std::vector<png_byte> bytes(display.rgba.size());
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const float v = std::isfinite(display.rgba[i]) ? std::clamp(display.rgba[i], 0.0f, 1.0f) : 0.0f;
    bytes[i] = static_cast<png_byte>(std::lround(v * 255.0f));
  }
  return bytes;
}
}  // namespace

// Encoded in memory, then written with every write and the close checked (io/atomic_file.h).
void WritePng(const std::filesystem::path& path, const Image& display) {
  const std::string png = EncodePng(display);
  WriteBytesAtomically(path, png.data(), png.size());
}

// libpng's simplified API (png_image, libpng >= 1.6): no setjmp in C++ frames.
std::string EncodePng(const Image& display) {
  const std::vector<png_byte> bytes = Quantize(display);
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(display.width);
  image.height = static_cast<png_uint_32>(display.height);
  image.format = PNG_FORMAT_RGBA;
  png_alloc_size_t size = 0;
  // First call: the size; second: the bytes (libpng >= 1.6.29).
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, bytes.data(), 0, nullptr)) {
    const std::string msg = image.message;
    png_image_free(&image);
    throw std::runtime_error("PNG encoding failed: " + msg);
  }
  std::string out(size, '\0');
  if (!png_image_write_to_memory(&image, out.data(), &size, 0, bytes.data(), 0, nullptr)) {
    const std::string msg = image.message;
    png_image_free(&image);
    throw std::runtime_error("PNG encoding failed: " + msg);
  }
  out.resize(size);
  return out;
}

Image ReadPng(const std::filesystem::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    const std::string msg = image.message;
    png_image_free(&image);
    throw InputError(path, "cannot read PNG: " + msg);
  }
  // A few bytes of header can declare 2^31 x 2^31 pixels: the largest render is 8192 x 8192.
  constexpr std::uint64_t kMaxPixels = std::uint64_t{1} << 26;
  if (image.width == 0 || image.height == 0 ||
      std::uint64_t{image.width} * image.height > kMaxPixels) {
    const std::string size = std::to_string(image.width) + " x " + std::to_string(image.height);
    png_image_free(&image);
    throw InputError(path, "declares " + size + " pixels (at most 2^26)");
  }
  image.format = PNG_FORMAT_RGBA;
  std::vector<png_byte> bytes(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, bytes.data(), 0, nullptr)) {
    const std::string msg = image.message;
    png_image_free(&image);
    throw InputError(path, "corrupt PNG: " + msg);
  }
  Image img(static_cast<int>(image.width), static_cast<int>(image.height));
  for (std::size_t i = 0; i < bytes.size(); ++i) img.rgba[i] = bytes[i] / 255.0f;
  return img;
}

void WriteExr(const std::filesystem::path& path, const Image& linear) {
  ExrMemoryOStream stream(path.string());  // io/exr_memory_stream.h: checked writes
  try {
    Imf::Header header(linear.width, linear.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const char* names[4] = {"R", "G", "B", "A"};
    for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
    Imf::FrameBuffer fb;
    const size_t xs = 4 * sizeof(float), ys = xs * static_cast<size_t>(linear.width);
    for (int c = 0; c < 4; ++c) {
      fb.insert(names[c],
                Imf::Slice(Imf::FLOAT,
                           const_cast<char*>(reinterpret_cast<const char*>(linear.rgba.data() + c)),
                           xs, ys));
    }
    Imf::OutputFile out(stream, header);  // its destructor writes the line-offset table
    out.setFrameBuffer(fb);
    out.writePixels(linear.height);
  } catch (const std::exception& e) {
    throw OutputError(path, std::string("OpenEXR: ") + e.what());
  }
  WriteBytesAtomically(path, stream.bytes().data(), stream.bytes().size());
}

Image ReadExr(const std::filesystem::path& path) {
  try {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    Image img(w, h);
    Imf::FrameBuffer fb;
    const size_t xs = 4 * sizeof(float), ys = xs * static_cast<size_t>(w);
    char* base = reinterpret_cast<char*>(img.rgba.data()) -
                 (static_cast<std::ptrdiff_t>(dw.min.x) * static_cast<std::ptrdiff_t>(xs)) -
                 (static_cast<std::ptrdiff_t>(dw.min.y) * static_cast<std::ptrdiff_t>(ys));
    const char* names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c) {
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys, 1, 1,
                                     c == 3 ? 1.0 : 0.0));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot read OpenEXR: ") + e.what());
  }
}

void WriteImageByExtension(const std::filesystem::path& path, const Image& linear,
                           const Image& display) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".exr") {
    WriteExr(path, linear);
  } else if (ext == ".png") {
    WritePng(path, display);
  } else {
    throw InputError(path, "unknown image extension '" + ext + "' (expected .png or .exr)");
  }
}

}  // namespace brdfit
