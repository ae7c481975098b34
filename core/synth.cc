#include "core/synth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace brdfit {

namespace {

// SplitMix64 output function (Vigna, splitmix64.c): a bijective 64-bit mixer.
std::uint64_t Mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

std::uint64_t Hash(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return Mix(Mix(Mix(seed) ^ stream) ^ index);
}

constexpr std::uint64_t kHoleStream = 1000;

}  // namespace

double SynthUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  // Top 53 bits, centred in their interval: never 0 or 1 (log and Box-Muller stay finite).
  return (static_cast<double>(Hash(seed, stream, index) >> 11) + 0.5) * 0x1p-53;
}

double SynthNormal(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  // Box & Muller 1958, "A Note on the Generation of Random Normal Deviates", eq. 1.
  const double u1 = SynthUniform(seed, 2 * stream, index);
  const double u2 = SynthUniform(seed, 2 * stream + 1, index);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

void ApplyNoiseAndHoles(Table& t, const SynthOptions& opt, SynthReport* report) {
  if (!(opt.noise >= 0) || !std::isfinite(opt.noise)) {
    throw std::invalid_argument("noise must be a finite sigma >= 0");
  }
  if (!(opt.missing_fraction >= 0 && opt.missing_fraction <= 1)) {
    throw std::invalid_argument("missing fraction must be in [0, 1]");
  }
  std::vector<std::pair<std::uint64_t, std::size_t>> keys;  // (random key, cell) of valid cells
  keys.reserve(t.valid.size());
  for (std::size_t idx = 0; idx < t.valid.size(); ++idx) {
    if (!t.valid[idx]) continue;
    keys.emplace_back(Hash(opt.seed, kHoleStream, idx), idx);
    if (opt.noise > 0) {
      double* v = t.Value(idx);
      for (int c = 0; c < 3; ++c) v[c] *= std::exp(opt.noise * SynthNormal(opt.seed, c, idx));
    }
  }
  // Holes: the k valid cells with the smallest random keys (ties by index), so the count is
  // exact and the choice uniform.
  const auto k = static_cast<std::size_t>(std::llround(opt.missing_fraction * keys.size()));
  if (k > 0) {
    std::nth_element(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(k - 1), keys.end());
    for (std::size_t j = 0; j < k; ++j) t.valid[keys[j].second] = 0;
  }
  t.provenance.seed = opt.seed;
  t.provenance.noise = opt.noise;
  t.provenance.missing_fraction = opt.missing_fraction;
  if (report) report->removed = k;
}

Table SynthesizeTable(const Grid& grid, const BrdfEvalFn& eval, const SynthOptions& opt,
                      SynthReport* report) {
  SynthReport r;
  Table t = Table::Empty(grid);
  for (std::size_t idx = 0; idx < grid.NumCells(); ++idx) {
    // Same construction as Grid::CellAboveHorizon: FromHalfDiff(CellCentre(idx), phi_h = 0).
    const Geometry g = MakeGeometry(grid.CellCentre(idx), 0.0);
    if (!(g.cos_i > 0 && g.cos_o > 0)) {
      ++r.below_horizon;
      continue;
    }
    double* v = t.Value(idx);
    eval(g, v);
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
      ++r.non_finite;
    } else if (v[0] < 0 || v[1] < 0 || v[2] < 0) {
      ++r.negative;
    } else {
      t.valid[idx] = 1;
    }
  }
  ApplyNoiseAndHoles(t, opt, &r);
  t.provenance.source = "synthetic";
  t.provenance.generator = "brdfit synth";
  if (report) *report = r;
  return t;
}

}  // namespace brdfit
