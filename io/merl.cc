#include "io/merl.h"

#include <fcntl.h>
#include <unistd.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <fmt/core.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "io/atomic_file.h"
#include "core/error.h"
#include "core/sse2_finite.h"
#include "io/input_file.h"

namespace brdfit {

namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "MERL files are little-endian; add byte swapping for this platform");

namespace {

constexpr std::array<std::int32_t, 3> kMerlDims = {90, 90, 180};
constexpr std::array<const char*, 3> kDimNames = {"theta_h", "theta_d", "phi_d"};
constexpr std::array<const char*, 3> kChannelNames = {"R", "G", "B"};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// pread until `bytes` are read; false at end of file.
bool ReadAt(int fd, void* dst, std::size_t bytes, std::uintmax_t offset) {
  auto* p = static_cast<char*>(dst);
  while (bytes > 0) {
    const ssize_t got = ::pread(fd, p, bytes, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    p += got;
    bytes -= static_cast<std::size_t>(got);
    offset += static_cast<std::uintmax_t>(got);
  }
  return true;
}

std::string CellName(const Grid& g, std::size_t idx) {
  int ih, id, ip;
  g.Unindex(idx, &ih, &id, &ip);
  return fmt::format("cell {} (theta_h {}, theta_d {}, phi_d {})", idx, ih, id, ip);
}

}  // namespace

double MerlRawFromValue(double v, int channel) {
  const double s = kMerlChannelScale[channel];
  const double r0 = v / s;
  if (r0 * s == v || !std::isfinite(r0)) return r0;
  // r0 * s rounds to a neighbour of v: look one and two ulps either side of r0.
  for (int step = 1; step <= 2; ++step) {
    for (const double dir : {-HUGE_VAL, HUGE_VAL}) {
      double r = r0;
      for (int k = 0; k < step; ++k) r = std::nextafter(r, dir);
      if (r * s == v) return r;
    }
  }
  return r0;  // v is not a product raw * s (e.g. a synthetic value): nearest raw
}

Table ReadMerl(const fs::path& path, MerlReadReport* report) {
  const std::uintmax_t size = CheckInputFile(path);
  const auto expected = fmt::format("expected {}", kMerlFileBytes);
  if (size < kMerlHeaderBytes) {
    throw InputError(path, fmt::format("truncated header: file is {} bytes, {}", size, expected));
  }
  const Fd fd{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (fd.fd < 0) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::int32_t dims[3];
  if (!ReadAt(fd.fd, dims, sizeof(dims), 0)) throw InputError(path, "truncated header");
  // A file that is a MERL table of another grid has the size its header implies (or MERL's):
  // that gets the dimension that differs. Anything else (a text file, another format) is not
  // a MERL table at all, and is told so rather than given a dimension out of its first bytes.
  if (dims[0] != kMerlDims[0] || dims[1] != kMerlDims[1] || dims[2] != kMerlDims[2]) {
    const double implied = static_cast<double>(kMerlHeaderBytes) +
                           3.0 * sizeof(double) * dims[0] * double(dims[1]) * dims[2];
    if (size != kMerlFileBytes &&
        !(dims[0] > 0 && dims[1] > 0 && dims[2] > 0 && implied == static_cast<double>(size))) {
      throw InputError(
          path, fmt::format("not a table brdfit reads: no HDF5 or RGL .bsdf signature, and not a "
                            "MERL .binary (its header would give a {} x {} x {} grid, MERL's is "
                            "90 x 90 x 180 in {} bytes; the file is {} bytes)",
                            dims[0], dims[1], dims[2], kMerlFileBytes, size));
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (dims[k] != kMerlDims[k]) {
      throw InputError(path, fmt::format("header dimension {} ({} bins) is {}, expected {}", k + 1,
                                         kDimNames[k], dims[k], kMerlDims[k]));
    }
  }
  if (size < kMerlFileBytes) {
    throw InputError(path, fmt::format("truncated: file is {} bytes, {}", size, expected));
  }
  if (size > kMerlFileBytes) {
    throw InputError(path, fmt::format("file is {} bytes, {}", size, expected));
  }

  // The body is channel-planar; the table interleaves RGB. Read the three planes block by block
  // (cache-sized buffers) and interleave while scaling: one pass, no file-sized buffer.
  const Grid grid = Grid::Merl();
  const std::size_t n = grid.NumCells();
  constexpr std::size_t kBlock = 16384;  // cells per block: 3 x 128 KiB
  std::array<std::vector<double>, 3> plane;
  for (auto& p : plane) p.resize(kBlock);
  // Every cell's values and mask are written below (or the read throws).
  Table t = Table::ForOverwrite(grid);
  std::size_t negative = 0;
  for (std::size_t start = 0; start < n; start += kBlock) {
    const std::size_t m = std::min(kBlock, n - start);
    for (int c = 0; c < 3; ++c) {
      const std::uintmax_t offset = kMerlHeaderBytes + (c * n + start) * sizeof(double);
      if (!ReadAt(fd.fd, plane[c].data(), m * sizeof(double), offset)) {
        throw InputError(path, "truncated: body ended early while reading");
      }
    }
    std::size_t j = 0;
#if defined(__SSE2__)
    // Two cells at a time while all six values are finite (the same products and flags as the
    // loop below, which reports the first non-finite value).
    const __m128d zero = _mm_setzero_pd();
    const __m128d scale_r = _mm_set1_pd(kMerlChannelScale[0]);
    const __m128d scale_g = _mm_set1_pd(kMerlChannelScale[1]);
    const __m128d scale_b = _mm_set1_pd(kMerlChannelScale[2]);
    for (; j + 2 <= m; j += 2) {
      const __m128d r = _mm_loadu_pd(&plane[0][j]);
      const __m128d g = _mm_loadu_pd(&plane[1][j]);
      const __m128d b = _mm_loadu_pd(&plane[2][j]);
      const __m128d finite =
          _mm_and_pd(FiniteLanes(r), _mm_and_pd(FiniteLanes(g), FiniteLanes(b)));
      if (_mm_movemask_pd(finite) != 3) break;
      const __m128d sr = _mm_mul_pd(r, scale_r), sg = _mm_mul_pd(g, scale_g),
                    sb = _mm_mul_pd(b, scale_b);
      double* out = &t.rgb[3 * (start + j)];
      _mm_storeu_pd(out, _mm_unpacklo_pd(sr, sg));       // R0 G0
      _mm_storeu_pd(out + 2, _mm_shuffle_pd(sb, sr, 2));  // B0 R1
      _mm_storeu_pd(out + 4, _mm_unpackhi_pd(sg, sb));    // G1 B1
      const int neg = _mm_movemask_pd(
          _mm_or_pd(_mm_cmplt_pd(r, zero), _mm_or_pd(_mm_cmplt_pd(g, zero), _mm_cmplt_pd(b, zero))));
      t.valid[start + j] = !(neg & 1);
      t.valid[start + j + 1] = !(neg & 2);
      negative += static_cast<std::size_t>((neg & 1) + ((neg >> 1) & 1));
    }
#endif
    for (; j < m; ++j) {
      const std::size_t i = start + j;
      const double r[3] = {plane[0][j], plane[1][j], plane[2][j]};
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(r[c])) {
          throw InputError(path,
                           fmt::format("{} at {}, channel {}", std::isnan(r[c]) ? "NaN" : "Inf",
                                       CellName(grid, i), kChannelNames[c]));
        }
        t.rgb[3 * i + c] = r[c] * kMerlChannelScale[c];  // channel scale applied once, here
      }
      const bool is_negative = r[0] < 0 || r[1] < 0 || r[2] < 0;
      t.valid[i] = !is_negative;
      negative += is_negative;
    }
  }
  t.provenance.source = path.string();
  t.provenance.generator = "merl";
  if (report) report->negative_cells = negative;
  return t;
}

void WriteMerl(const Table& t, const fs::path& path) {
  if (!(t.grid == Grid::Merl())) {
    throw InputError(path, fmt::format("MERL files hold only the 90x90x180 grid with sqrt theta_h "
                                       "mapping; this table is {}x{}x{} ({})",
                                       t.grid.n_theta_h, t.grid.n_theta_d, t.grid.n_phi_d,
                                       ToString(t.grid.theta_h_mapping)));
  }
  const std::size_t n = t.grid.NumCells();
  std::vector<double> raw(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* v = t.Value(i);
    const bool finite = std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
    if (t.valid[i]) {
      if (!finite || v[0] < 0 || v[1] < 0 || v[2] < 0) {
        throw InputError(path, fmt::format("{} is valid but holds ({}, {}, {}); MERL can store "
                                           "only finite non-negative valid values",
                                           CellName(t.grid, i), v[0], v[1], v[2]));
      }
      for (int c = 0; c < 3; ++c) raw[c * n + i] = MerlRawFromValue(v[c], c);
    } else if (finite && (v[0] < 0 || v[1] < 0 || v[2] < 0)) {
      for (int c = 0; c < 3; ++c) raw[c * n + i] = MerlRawFromValue(v[c], c);  // as read
    } else {
      for (int c = 0; c < 3; ++c) raw[c * n + i] = -1.0;
    }
  }
  WriteFileAtomically(path, [&](const fs::path& tmp) {
    std::unique_ptr<std::FILE, FileCloser> f(std::fopen(tmp.c_str(), "wb"));
    if (!f) {
      throw OutputError(
          path, "cannot create temporary file " + tmp.string() + ": " + std::strerror(errno));
    }
    if (std::fwrite(kMerlDims.data(), sizeof(std::int32_t), 3, f.get()) != 3 ||
        std::fwrite(raw.data(), sizeof(double), raw.size(), f.get()) != raw.size() ||
        std::fflush(f.get()) != 0) {
      throw OutputError(path, std::string("write failed: ") + std::strerror(errno));
    }
    // A full disk or an I/O error may show only at the close.
    if (std::fclose(f.release()) != 0) {
      throw OutputError(path, std::string("write failed at close: ") + std::strerror(errno));
    }
  });
}

}  // namespace brdfit
