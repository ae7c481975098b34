#include "core/provenance.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <ctime>

#include "core/table.h"

namespace brdfit {

namespace {

std::string& CommandLineStorage() {
  static std::string s;
  return s;
}

// A shell word as typed: bare when it holds only safe characters, else in single quotes.
std::string ShellQuoted(std::string_view a) {
  const bool safe = !a.empty() && a.find_first_not_of(
                                      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                      "0123456789-_./:=,+@%") == std::string_view::npos;
  if (safe) return std::string(a);
  std::string out = "'";
  for (char c : a) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// One word mixed into the state: the SplitMix64 finalizer (Steele, Lea, Flood 2014; Stafford's
// Mix13 constants) applied to the state xor the word.
std::uint64_t Mix(std::uint64_t h, std::uint64_t w) {
  h ^= w + 0x9e3779b97f4a7c15ULL;
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  h ^= h >> 31;
  return h;
}

}  // namespace

std::string_view BrdfitVersion() {
  return BRDFIT_VERSION;
}

void SetCommandLine(int argc, const char* const* argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) {
    if (i) s += ' ';
    s += ShellQuoted(argv[i]);
  }
  CommandLineStorage() = s;
}

const std::string& CommandLine() {
  return CommandLineStorage();
}

RunProvenance CurrentRunProvenance(bool with_run_details) {
  RunProvenance p;
  p.version = std::string(BrdfitVersion());
  if (!with_run_details) return p;
  p.command_line = CommandLine();
  // SOURCE_DATE_EPOCH (reproducible-builds.org/specs/source-date-epoch): a fixed date for
  // reproducible outputs, seconds since 1970 UTC.
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    char* end = nullptr;
    const long long v = std::strtoll(epoch, &end, 10);
    if (end != epoch && *end == '\0' && v >= 0) now = static_cast<std::time_t>(v);
  }
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  p.created = buf;
  return p;
}

std::string TableContentHash(const Table& t) {
  std::uint64_t h = Mix(0, 0x7461626c65ULL);  // "table"
  h = Mix(h, static_cast<std::uint64_t>(t.grid.n_theta_h));
  h = Mix(h, static_cast<std::uint64_t>(t.grid.n_theta_d));
  h = Mix(h, static_cast<std::uint64_t>(t.grid.n_phi_d));
  h = Mix(h, static_cast<std::uint64_t>(t.grid.theta_h_mapping));
  // The bulk: FNV-1a steps over 8-byte words (one multiply each by the 64-bit FNV prime) in
  // four lanes, so that a MERL table (4.4 M words) hashes in a few ms; the lanes and the
  // lengths are mixed at the end.
  constexpr std::uint64_t kPrime = 1099511628211ULL;
  std::uint64_t lane[4] = {h, ~h, h ^ 0x5555555555555555ULL, h ^ 0xaaaaaaaaaaaaaaaaULL};
  const std::size_t n = t.rgb.size();
  // Word i goes to lane i mod 4; four words per step in locals, so that the four multiply chains
  // run side by side (the lanes in an indexed array kept them in memory: 3x slower).
  std::uint64_t l0 = lane[0], l1 = lane[1], l2 = lane[2], l3 = lane[3];
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    std::uint64_t w[4];
    std::memcpy(w, &t.rgb[i], sizeof w);
    l0 = (l0 ^ w[0]) * kPrime;
    l1 = (l1 ^ w[1]) * kPrime;
    l2 = (l2 ^ w[2]) * kPrime;
    l3 = (l3 ^ w[3]) * kPrime;
  }
  lane[0] = l0, lane[1] = l1, lane[2] = l2, lane[3] = l3;
  for (; i < n; ++i) {
    std::uint64_t w;
    std::memcpy(&w, &t.rgb[i], 8);
    lane[i & 3] = (lane[i & 3] ^ w) * kPrime;
  }
  for (std::size_t k = 0; k < t.valid.size(); k += 8) {
    std::uint64_t w = 0;
    std::memcpy(&w, &t.valid[k], std::min<std::size_t>(8, t.valid.size() - k));
    lane[(k / 8) & 3] = (lane[(k / 8) & 3] ^ w) * kPrime;
  }
  std::uint64_t out = Mix(h, n);
  out = Mix(out, t.valid.size());
  for (const std::uint64_t l : lane) out = Mix(out, l);
  return fmt::format("t64:{:016x}", out);
}

}  // namespace brdfit
