// Fuzz harness: MERL .binary reader (io/merl.h).
//
// A MERL file is 34,992,012 bytes, far more than a fuzzer input, so the first byte picks a mode:
//  * bit 0 clear: the rest of the input is the file as is (header checks, short and odd sizes);
//  * bit 0 set:   "expanded": 12 header bytes from the input, then one size byte (0..239: the exact
//          MERL size, 240..255: the exact size -8..+7 bytes), then the body of that size tiled
//          with the remaining input bytes (zeros if none). This reaches the value checks (NaN,
//          Inf, negative masking, denormals) with full-size files.
// After a successful read: grid, sizes and masking invariants; with bit 1 of the first byte set,
// also an exact write -> read round trip (io/merl.h promises Table -> file -> Table is exact).
// The round trip is optional because it triples the cost of a full-size input.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/merl.h"

namespace brdfit::fuzz {

namespace {

std::vector<char> Expand(ByteReader& in) {
  const std::string_view header = in.Bytes(kMerlHeaderBytes);
  const std::uint8_t size_code = in.U8();
  const std::string_view pattern = in.Rest();
  std::int64_t size = static_cast<std::int64_t>(kMerlFileBytes);
  if (size_code >= 240) size += static_cast<int>(size_code) - 248;
  std::vector<char> file(static_cast<std::size_t>(size), 0);
  std::memcpy(file.data(), header.data(), header.size());
  if (!pattern.empty() && file.size() > kMerlHeaderBytes) {
    // Tile by doubling the filled prefix: O(log n) copies.
    const std::size_t body = file.size() - kMerlHeaderBytes;
    char* b = file.data() + kMerlHeaderBytes;
    std::size_t filled = std::min(pattern.size(), body);
    std::memcpy(b, pattern.data(), filled);
    while (filled < body) {
      const std::size_t n = std::min(filled, body - filled);
      std::memcpy(b + filled, b, n);
      filled += n;
    }
  }
  return file;
}

void CheckTable(const Table& t, const MerlReadReport& report) {
  CheckInvariant(t.grid == Grid::Merl(), "grid is not MERL's");
  const std::size_t n = t.grid.NumCells();
  CheckInvariant(t.rgb.size() == 3 * n && t.valid.size() == n, "array sizes");
  std::size_t masked = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double* v = t.Value(i);
    if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) {
      Violation("non-finite value in cell " + std::to_string(i));
    }
    // Masked iff a raw channel was negative. A negative raw below ~1e-320 scales to -0.0, so
    // the sign bit (not v < 0) is what a masked cell must show (fuzz finding, harness-side).
    const bool negative = v[0] < 0 || v[1] < 0 || v[2] < 0;
    const bool sign = std::signbit(v[0]) || std::signbit(v[1]) || std::signbit(v[2]);
    if (t.valid[i] ? negative : !sign) {
      Violation("mask disagrees with the sign, cell " + std::to_string(i));
    }
    masked += !t.valid[i];
  }
  CheckInvariant(masked == report.negative_cells, "negative_cells count");
}

}  // namespace

int FuzzMerl(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const std::uint8_t mode = in.U8();
  const bool expanded = mode & 1;
  const bool round_trip = mode & 2;
  std::filesystem::path path;
  if (expanded) {
    const std::vector<char> file = Expand(in);
    path = WriteScratch("merl-in.binary", file.data(), file.size());
  } else {
    const std::string_view file = in.Rest();
    path = WriteScratch("merl-in.binary", file.data(), file.size());
  }

  Table t;
  MerlReadReport report;
  try {
    t = ReadMerl(path, &report);
  } catch (const InputError&) {
    return 0;  // rejected with a message: the expected outcome for bad input
  }
  CheckTable(t, report);
  if (!round_trip) return 0;

  const std::filesystem::path out = ScratchDir() / "merl-out.binary";
  WriteMerl(t, out);  // a table read from MERL must be writable as MERL
  const Table back = ReadMerl(out);
  CheckInvariant(back.valid == t.valid, "round trip changed the mask");
  // Exact for valid cells. A masked cell's value is meaningless (core/table.h); the writer keeps
  // it only when it is negative, so a masked -0.0 comes back as -1 * scale.
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    if (t.valid[i] && std::memcmp(back.Value(i), t.Value(i), 3 * sizeof(double)) != 0) {
      Violation("round trip changed valid cell " + std::to_string(i));
    }
  }
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzMerl)
