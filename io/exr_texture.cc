#include "io/exr_texture.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTestFile.h>
#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/exr_memory_stream.h"
#include "io/input_file.h"

namespace brdfit {
namespace {

constexpr const char* kChannels[3] = {"R", "G", "B"};
constexpr int kMaxSide = 1 << 15;  // refuse absurd headers before allocating
// ... and absurd areas: 4096 x 4096 float RGB is 201 MB. A header declaring 32768 x 32768 and
// storing nothing made the reader allocate 12 GB (fuzz/regressions/exr/crafted-*).
constexpr long long kMaxPixels = 1LL << 24;

// OpenEXR 3.1 allocates each header attribute's declared size before reading it, so a few
// bytes declaring a 2 GB attribute cost a 2 GB allocation (fuzz_exr: 75 inputs in 10 min).
// Walks the header(s) (OpenEXR file layout: magic, version, then per attribute name\0 type\0
// int32 size, value; an empty name ends a header; multi-part files end with an empty header)
// and rejects a declared size larger than the rest of the file. Only reads the first 1 MiB.
void CheckAttributeSizes(const std::filesystem::path& path, std::uintmax_t file_size) {
  const std::vector<char> b = ReadFilePrefix(path, std::size_t{1} << 20);
  std::size_t pos = 8;
  if (b.size() < pos) return;  // OpenEXR reports the truncation itself
  const bool multipart = (static_cast<unsigned char>(b[5]) & 0x10) != 0;  // version bit 12
  auto read_name = [&](std::string* out) {
    const auto end = std::find(b.begin() + static_cast<std::ptrdiff_t>(pos), b.end(), '\0');
    if (end == b.end()) return false;
    out->assign(b.begin() + static_cast<std::ptrdiff_t>(pos), end);
    pos = static_cast<std::size_t>(end - b.begin()) + 1;
    return true;
  };
  std::string name, type;
  for (bool header_empty = true;;) {
    if (!read_name(&name)) return;
    if (name.empty()) {  // end of a header
      if (!multipart || header_empty) return;
      header_empty = true;
      continue;
    }
    header_empty = false;
    if (!read_name(&type) || pos + 4 > b.size()) return;
    std::int32_t size = 0;
    std::memcpy(&size, &b[pos], 4);  // little-endian, as this platform (static_assert in merl.cc)
    pos += 4;
    if (size < 0 || static_cast<std::uintmax_t>(size) > file_size - pos) {
      throw InputError(path, fmt::format("damaged OpenEXR header: attribute '{}' declares {} bytes, "
                                         "the file has {} left",
                                         PrintableExcerpt(name), size, file_size - pos));
    }
    pos += static_cast<std::size_t>(size);
  }
}

}  // namespace

void WriteRgbExr(const std::filesystem::path& path, const RgbImage& image,
                 const ExrAttributes& attributes) {
  if (image.width <= 0 || image.height <= 0 || image.width > kMaxSide || image.height > kMaxSide ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * image.height) {
    throw InputError(path, fmt::format("cannot write a {} x {} image from {} floats", image.width,
                                       image.height, image.rgb.size()));
  }
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;  // lossless
  for (const char* c : kChannels) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
  for (const auto& [name, value] : attributes) {
    if (name.empty() || header.find(name) != header.end()) {
      throw InputError(path, "EXR attribute name '" + name + "' is empty or reserved");
    }
    header.insert(name, Imf::StringAttribute(value));
  }
  ExrMemoryOStream stream(path.string());
  try {
    Imf::OutputFile file(stream, header);  // its destructor writes the line-offset table
    Imf::FrameBuffer fb;
    // The slices only read from the buffer; OpenEXR's Slice takes a non-const pointer.
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
    const std::size_t xs = 3 * sizeof(float);
    const std::size_t ys = xs * image.width;
    for (int c = 0; c < 3; ++c) {
      fb.insert(kChannels[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
    }
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    throw OutputError(path, std::string("writing OpenEXR failed: ") + e.what());
  }
  WriteBytesAtomically(path, stream.bytes().data(), stream.bytes().size());
}

RgbImage ReadRgbExr(const std::filesystem::path& path, ExrAttributes* attributes) {
  const std::uintmax_t file_size = CheckInputFile(path);
  if (!Imf::isOpenExrFile(path.c_str())) throw InputError(path, "not an OpenEXR file");
  CheckAttributeSizes(path, file_size);
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i dw = header.dataWindow();
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    if (w <= 0 || h <= 0 || w > kMaxSide || h > kMaxSide || w * h > kMaxPixels) {
      throw InputError(path, fmt::format("unsupported data window {} x {}", w, h));
    }
    for (const char* c : kChannels) {
      if (!header.channels().findChannel(c)) {
        throw InputError(path, std::string("missing channel ") + c + " (expected R, G, B)");
      }
    }
    RgbImage image = RgbImage::Filled(static_cast<int>(w), static_cast<int>(h), 0.0f);
    Imf::FrameBuffer fb;
    const std::size_t xs = 3 * sizeof(float);
    for (int c = 0; c < 3; ++c) {
      fb.insert(kChannels[c],
                Imf::Slice::Make(Imf::FLOAT, image.rgb.data() + c, dw, xs, xs * image.width));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (attributes) {
      attributes->clear();
      for (auto it = header.begin(); it != header.end(); ++it) {
        if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
          (*attributes)[it.name()] = s->value();
        }
      }
    }
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "damaged or unreadable OpenEXR file: " + PrintableExcerpt(e.what()));
  }
}

}  // namespace brdfit
