#include "io/exr_texture.h"

#include <OpenEXR/ImfAttribute.h>
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
#include <map>
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

// How many value bytes OpenEXR 3.1 reads for an attribute of a known type whose reader ignores
// the declared size (ImfStandardAttributes / ImfTypedAttribute readValueFrom: fixed-size
// values); 0 when the type is not one of them.
std::size_t FixedValueSize(const std::string& type) {
  static const std::map<std::string, std::size_t> kSizes = {{"box2i", 16},
                                                            {"box2f", 16},
                                                            {"chromaticities", 32},
                                                            {"compression", 1},
                                                            {"deepImageState", 1},
                                                            {"double", 8},
                                                            {"envmap", 1},
                                                            {"float", 4},
                                                            {"int", 4},
                                                            {"keycode", 28},
                                                            {"lineOrder", 1},
                                                            {"m33f", 36},
                                                            {"m33d", 72},
                                                            {"m44f", 64},
                                                            {"m44d", 128},
                                                            {"rational", 8},
                                                            {"tiledesc", 9},
                                                            {"timecode", 8},
                                                            {"v2i", 8},
                                                            {"v2f", 8},
                                                            {"v2d", 16},
                                                            {"v3i", 12},
                                                            {"v3f", 12},
                                                            {"v3d", 24}};
  const auto it = kSizes.find(type);
  return it == kSizes.end() ? 0 : it->second;
}

// OpenEXR 3.1 allocates what a header declares before reading it: an attribute's declared size
// (a few bytes declaring a 2 GB string cost a 2 GB allocation), and for some types what their
// value declares, while it parses other types without looking at the declared size (a channel
// list ends at its empty name, a box2i is 16 bytes), so a declared size that disagrees with the
// value makes OpenEXR read the next attribute from inside this one. Walks the header(s) as
// OpenEXR parses them (OpenEXR file layout: magic, version, then per attribute name\0 type\0
// int32 size, value; an empty name ends a header; multi-part files end with an empty header)
// and refuses a size larger than the rest of the file, a size that disagrees with what OpenEXR
// will read, and types whose reader allocates from the value. Only reads the first 1 MiB.
void CheckAttributeSizes(const std::filesystem::path& path, std::uintmax_t file_size) {
  const std::vector<char> b = ReadFilePrefix(path, std::size_t{1} << 20);
  std::size_t pos = 8;
  if (b.size() < pos) return;  // OpenEXR reports the truncation itself
  const bool multipart = (static_cast<unsigned char>(b[5]) & 0x10) != 0;  // version bit 12
  auto read_name = [&](std::size_t* at, std::string* out) {
    const auto end = std::find(b.begin() + static_cast<std::ptrdiff_t>(*at), b.end(), '\0');
    if (end == b.end()) return false;
    out->assign(b.begin() + static_cast<std::ptrdiff_t>(*at), end);
    *at = static_cast<std::size_t>(end - b.begin()) + 1;
    return true;
  };
  auto damaged = [&](const std::string& name, const std::string& type, const std::string& what) {
    return InputError(path, fmt::format("damaged OpenEXR header: attribute '{}' of type '{}' {}",
                                        PrintableExcerpt(name), PrintableExcerpt(type), what));
  };
  std::string name, type;
  for (bool header_empty = true;;) {
    if (!read_name(&pos, &name)) return;
    if (name.empty()) {  // end of a header
      if (!multipart || header_empty) return;
      header_empty = true;
      continue;
    }
    header_empty = false;
    if (!read_name(&pos, &type) || pos + 4 > b.size()) return;
    std::int32_t size = 0;
    std::memcpy(&size, &b[pos], 4);  // little-endian, as this platform (static_assert in merl.cc)
    pos += 4;
    if (size < 0 || static_cast<std::uintmax_t>(size) > file_size - pos) {
      throw damaged(name, type,
                    fmt::format("declares {} bytes, the file has {} left", size, file_size - pos));
    }
    const std::size_t declared = static_cast<std::size_t>(size);
    if (const std::size_t fixed = FixedValueSize(type); fixed != 0) {
      if (declared != fixed) {
        throw damaged(name, type,
                      fmt::format("declares {} bytes, the type has {}", declared, fixed));
      }
    } else if (type == "chlist") {
      // ImfChannelListAttribute: per channel name\0, int32 pixel type, uint8 pLinear, 3 reserved
      // bytes, int32 xSampling, int32 ySampling; an empty name ends the list.
      std::size_t at = pos;
      std::string channel;
      for (;;) {
        if (!read_name(&at, &channel)) return;  // beyond the prefix read: OpenEXR checks it
        if (channel.empty()) break;
        at += 16;
        if (at > b.size()) return;
      }
      if (at - pos != declared) {
        throw damaged(name, type,
                      fmt::format("declares {} bytes, its channel list is not that "
                                  "long",
                                  declared));
      }
    } else if (Imf::Attribute::knownType(type.c_str()) && type != "string" &&
               type != "stringvector" && type != "floatvector") {
      // Known types whose reader allocates what the value declares (preview, idmanifest): a
      // texture has no use for them.
      throw damaged(name, type, "is not read by brdfit (re-save the image without it)");
    }
    pos += declared;
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
    // The pixels must fit in the file: zlib's largest compression factor is 1032:1 (zlib
    // technical details, "Maximum compression factor") and RLE's is smaller, so a small file
    // declaring a large window is refused before OpenEXR allocates and decodes it. A codec that
    // can store more (a constant image in PIZ or DWA) is refused too: re-save with ZIP, as
    // brdfit writes.
    if (static_cast<double>(w) * h * sizeof(float) * 3 > 1032.0 * static_cast<double>(file_size)) {
      throw InputError(path, fmt::format("data window {} x {} needs more pixel data than {} bytes "
                                         "can hold (at most 1032:1 compressed; re-save with ZIP)",
                                         w, h, file_size));
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
