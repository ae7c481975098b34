// Summary of the rendered-image metric (docs/accuracy.md) over materials, as the study tables of
// docs/accuracy.md give it: mean and lowest linear PSNR, the median over materials of each
// material's median relative luminance error, the worst material's, and how many materials reach
// the targets (>= 30 dB, <= 15 %). Shared by bench_accuracy (fits) and bench_factor_accuracy
// (factorizations), so that both tables are computed alike.
#pragma once

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "core/metrics.h"

namespace brdfit::bench {

inline constexpr double kTargetPsnrDb = 30.0;
inline constexpr double kTargetMedianLum = 0.15;

struct RenderedSummary {
  std::size_t count = 0;   // materials scored (ok)
  std::size_t failed = 0;  // metric not ok: left out of every column
  double mean_psnr_db = 0, min_psnr_db = 0;
  double median_lum = 0;  // median over materials of the per-material median error
  double worst_lum = 0;
  std::string worst_material;
  int at_psnr_target = 0, at_lum_target = 0;
};

// The median of a list (the mean of the two middle elements for an even count).
inline double MedianOf(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

class RenderedSummarizer {
 public:
  void Add(const std::string& material, const RenderedError& e) {
    if (!e.ok) {
      ++s_.failed;
      return;
    }
    psnr_.push_back(e.psnr_db);
    lum_.push_back(e.median_rel_error);
    s_.at_psnr_target += e.psnr_db >= kTargetPsnrDb;
    s_.at_lum_target += e.median_rel_error <= kTargetMedianLum;
    if (s_.worst_material.empty() || e.median_rel_error > s_.worst_lum) {
      s_.worst_lum = e.median_rel_error;
      s_.worst_material = material;
    }
  }
  RenderedSummary Get() const {
    RenderedSummary s = s_;
    s.count = psnr_.size();
    double sum = 0;
    for (double p : psnr_) sum += p;
    s.mean_psnr_db = psnr_.empty() ? 0 : sum / static_cast<double>(psnr_.size());
    s.min_psnr_db = psnr_.empty() ? 0 : *std::min_element(psnr_.begin(), psnr_.end());
    s.median_lum = MedianOf(lum_);
    return s;
  }

 private:
  RenderedSummary s_;
  std::vector<double> psnr_, lum_;
};

// One header line and one line per configuration, fixed columns.
inline void PrintRenderedSummaryHeader(std::FILE* out) {
  fmt::print(out, "{:<34} {:>5} {:>9} {:>9} {:>10} {:>10} {:>8} {:>8}\n", "configuration", "fits",
             "mean dB", "min dB", "med lum", "worst lum", ">=30dB", "<=15%");
}
inline void PrintRenderedSummaryRow(std::FILE* out, const std::string& config,
                                    const RenderedSummary& s) {
  fmt::print(out, "{:<34} {:>5} {:>9.2f} {:>9.2f} {:>9.1f}% {:>9.1f}% {:>8} {:>8}  worst: {}{}\n",
             config, s.count, s.mean_psnr_db, s.min_psnr_db, 100 * s.median_lum,
             100 * s.worst_lum, s.at_psnr_target, s.at_lum_target, s.worst_material,
             s.failed ? fmt::format(" ({} failed, left out)", s.failed) : std::string());
}

}  // namespace brdfit::bench
