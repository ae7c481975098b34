#include "report/bench_csv.h"

#include <fmt/core.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

namespace brdfit::report {

namespace {

// ---- The bench row's schema ----------------------------------------------------------------
// One row per column in the order written, or per group of columns drawn from core/metrics.h's
// tables (the error metrics, the rendered summary, the regions): the writer, the reader and the
// header iterate it; adding a column is one row here (and its member of BenchPoint).
enum class BenchKind {
  kText,             // any string, RFC 4180 quoted
  kMillis,           // a time in ms, >= 0; absent or empty reads as 0
  kCount,            // an integer >= 0; absent reads as 0
  kSmallCount,       // an integer in [0, INT_MAX]; absent reads as 0
  kMetricOk,         // "1" or "0"; absent: the primary error metric is a number
  kDegrees,          // an angle in [0, 90] degrees; absent or empty reads as 0
  kErrorMetrics,     // core/metrics.h kErrorMetrics, one column each
  kRenderedSummary,  // core/metrics.h kRenderedSummary, one column each; all or none
  kRegions,          // REGION_psnr_db and REGION_median_rel_error per region; both or neither
};
struct BenchColumn {
  const char* name;  // nullptr for a group
  BenchKind kind;
  bool required;  // a reader refuses a file without this column
  std::string& (*text)(BenchPoint&) = nullptr;
  double& (*number)(BenchPoint&) = nullptr;  // kMillis, kDegrees
  std::size_t& (*count)(BenchPoint&) = nullptr;
  int& (*small_count)(BenchPoint&) = nullptr;
};
constexpr BenchColumn kBenchColumns[] = {
    {"material", BenchKind::kText, true, [](BenchPoint& b) -> std::string& { return b.material; }},
    {"table", BenchKind::kText, false, [](BenchPoint& b) -> std::string& { return b.table; }},
    {"model", BenchKind::kText, true, [](BenchPoint& b) -> std::string& { return b.model; }},
    {"loss", BenchKind::kText, false, [](BenchPoint& b) -> std::string& { return b.loss; }},
    {"budget", BenchKind::kText, true, [](BenchPoint& b) -> std::string& { return b.budget; }},
    {"status", BenchKind::kText, false, [](BenchPoint& b) -> std::string& { return b.status; }},
    {"time_ms", BenchKind::kMillis, true, nullptr,
     [](BenchPoint& b) -> double& { return b.time_ms; }},
    {"prepare_ms", BenchKind::kMillis, false, nullptr,
     [](BenchPoint& b) -> double& { return b.prepare_ms; }},
    {"init_ms", BenchKind::kMillis, false, nullptr,
     [](BenchPoint& b) -> double& { return b.init_ms; }},
    {"solve_ms", BenchKind::kMillis, false, nullptr,
     [](BenchPoint& b) -> double& { return b.solve_ms; }},
    {nullptr, BenchKind::kErrorMetrics, true},
    {"metric_ok", BenchKind::kMetricOk, false},
    {"metric_cells", BenchKind::kCount, false, nullptr, nullptr,
     [](BenchPoint& b) -> std::size_t& { return b.metrics.cells; }},
    {"weighting", BenchKind::kText, false,
     [](BenchPoint& b) -> std::string& { return b.metrics.weighting; }},
    {"cutoff_deg", BenchKind::kDegrees, false, nullptr,
     [](BenchPoint& b) -> double& { return b.metrics.cutoff_deg; }},
    {"fit_cells", BenchKind::kCount, false, nullptr, nullptr,
     [](BenchPoint& b) -> std::size_t& { return b.fit_cells; }},
    {"iterations", BenchKind::kSmallCount, false, nullptr, nullptr, nullptr,
     [](BenchPoint& b) -> int& { return b.iterations; }},
    {"message", BenchKind::kText, false, [](BenchPoint& b) -> std::string& { return b.message; }},
    // Columns appended later: files written before them lack them.
    {nullptr, BenchKind::kRenderedSummary, false},
    {nullptr, BenchKind::kRegions, false},
};

std::string RegionColumn(int region, const char* quantity) {
  return std::string(kRenderedRegionNames[region]) + "_" + quantity;
}

// The names of a row of kBenchColumns, in order.
std::vector<std::string> ColumnNames(const BenchColumn& c) {
  switch (c.kind) {
    case BenchKind::kErrorMetrics: {
      std::vector<std::string> names;
      for (const ErrorMetricField& f : kErrorMetrics) names.push_back(f.name);
      return names;
    }
    case BenchKind::kRenderedSummary: {
      std::vector<std::string> names;
      for (const RenderedSummaryField& f : kRenderedSummary) names.push_back(f.name);
      return names;
    }
    case BenchKind::kRegions: {
      std::vector<std::string> names;
      for (int g = 0; g < kRenderedRegions; ++g) {
        names.push_back(RegionColumn(g, "psnr_db"));
        names.push_back(RegionColumn(g, "median_rel_error"));
      }
      return names;
    }
    default:
      return {c.name};
  }
}

}  // namespace

const std::vector<std::string>& BenchCsvColumns() {
  static const std::vector<std::string> columns = [] {
    std::vector<std::string> names;
    for (const BenchColumn& c : kBenchColumns) {
      for (std::string& n : ColumnNames(c)) names.push_back(std::move(n));
    }
    return names;
  }();
  return columns;
}

namespace {

std::string Quote(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// Shortest round-trip text of a double; "nan" for non-finite (never written by brdfit, read
// back as NaN).
std::string Num(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "nan"; }

// A number of the rendered-image metric; empty when it was not computed (ok = false).
std::string Rendered(const RenderedError& r, double v) { return r.ok ? Num(v) : std::string(); }

}  // namespace

std::string BenchCsvText(const std::vector<BenchPoint>& points) {
  std::string out;
  const auto& cols = BenchCsvColumns();
  for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i];
  out += "\n";
  for (const BenchPoint& point : points) {
    BenchPoint b = point;  // the table's accessors give references into a point
    const RenderedError& re = b.metrics.rendered;
    std::vector<std::string> fields;
    for (const BenchColumn& c : kBenchColumns) {
      switch (c.kind) {
        case BenchKind::kText:
          fields.push_back(Quote(c.text(b)));
          break;
        case BenchKind::kMillis:
        case BenchKind::kDegrees:
          fields.push_back(Num(c.number(b)));
          break;
        case BenchKind::kCount:
          fields.push_back(std::to_string(c.count(b)));
          break;
        case BenchKind::kSmallCount:
          fields.push_back(std::to_string(c.small_count(b)));
          break;
        case BenchKind::kMetricOk:
          fields.push_back(b.metrics.ok ? "1" : "0");
          break;
        case BenchKind::kErrorMetrics:
          for (const ErrorMetricField& f : kErrorMetrics) fields.push_back(Num(b.metrics.*f.value));
          break;
        case BenchKind::kRenderedSummary:
          for (const RenderedSummaryField& f : kRenderedSummary) {
            fields.push_back(f.NotComputed(re) ? std::string() : Rendered(re, re.*f.value));
          }
          break;
        case BenchKind::kRegions:
          for (const RenderedRegionError& g : re.regions) {
            const bool judged = re.ok && g.lights > 0;
            fields.push_back(judged ? Num(g.psnr_db) : std::string());
            fields.push_back(judged ? Num(g.median_rel_error) : std::string());
          }
          break;
      }
    }
    for (std::size_t i = 0; i < fields.size(); ++i) out += (i ? "," : "") + fields[i];
    out += "\n";
  }
  return out;
}

void WriteBenchCsv(const std::filesystem::path& path, const std::vector<BenchPoint>& points) {
  WriteTextAtomically(path, BenchCsvText(points));
}

std::vector<std::string> SplitCsvRecord(const std::string& text, std::size_t* pos) {
  std::vector<std::string> fields;
  std::string field;
  std::size_t i = *pos;
  bool quoted = false, was_quoted = false;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        field += c;
      }
    } else if (c == '"' && field.empty() && !was_quoted) {
      quoted = was_quoted = true;
    } else if (c == ',') {
      fields.push_back(std::move(field));
      field.clear();
      was_quoted = false;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      ++i;
      break;
    } else {
      field += c;
    }
  }
  if (quoted) throw std::invalid_argument("unterminated quoted field");
  fields.push_back(std::move(field));
  *pos = i;
  return fields;
}

namespace {

// A number, or NaN for an empty field (not computed). brdfit never writes a non-finite number,
// so "nan" or "inf" is refused, not read as "no value".
double ParseDouble(const std::string& s, const std::filesystem::path& path, int line,
                   const std::string& column) {
  if (s.empty()) return NAN;
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) {
    throw InputError(path, fmt::format("line {}: column {}: '{}' is not a number", line, column,
                                       PrintableExcerpt(s, 64)));
  }
  if (!std::isfinite(v)) {
    throw InputError(path, fmt::format("line {}: column {}: '{}' is not finite", line, column,
                                       PrintableExcerpt(s, 64)));
  }
  return v;
}

// A time or an error: present and >= 0.
void RequireNonNegative(double v, const std::filesystem::path& path, int line,
                        const std::string& column) {
  if (std::isnan(v)) throw InputError(path, fmt::format("line {}: column {} is empty", line, column));
  if (v < 0) throw InputError(path, fmt::format("line {}: column {}: {} is negative", line, column, v));
}

long ParseInt(const std::string& s, const std::filesystem::path& path, int line,
              const std::string& column) {
  long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || v < 0) {
    throw InputError(path, fmt::format("line {}: column {}: '{}' is not a count", line, column,
                                       PrintableExcerpt(s, 64)));
  }
  return v;
}

}  // namespace

std::vector<BenchPoint> ReadBenchCsv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the bench CSV");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::size_t pos = 0;
  int line = 1;
  std::map<std::string, std::size_t> col;
  std::vector<std::string> header;
  try {
    header = SplitCsvRecord(text, &pos);
  } catch (const std::invalid_argument& e) {
    throw InputError(path, fmt::format("line 1: {}", e.what()));
  }
  // A column twice would leave the rows one field longer than the columns found by name.
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (!col.emplace(header[i], i).second) {
      throw InputError(
          path, fmt::format("line 1: column '{}' appears twice", PrintableExcerpt(header[i], 64)));
    }
  }
  for (const BenchColumn& c : kBenchColumns) {
    if (!c.required) continue;
    // Of the error metrics, the primary one: older files lack the later ones.
    const std::string name = c.kind == BenchKind::kErrorMetrics
                                 ? std::string(kErrorMetrics[kPrimaryErrorMetric].name)
                                 : std::string(c.name);
    if (!col.count(name)) {
      throw InputError(path, fmt::format("not a brdfit bench CSV: no column '{}'", name));
    }
  }
  std::vector<BenchPoint> points;
  while (pos < text.size()) {
    ++line;
    std::vector<std::string> f;
    try {
      f = SplitCsvRecord(text, &pos);
    } catch (const std::invalid_argument& e) {
      throw InputError(path, fmt::format("line {}: {}", line, e.what()));
    }
    if (f.size() == 1 && f[0].empty()) continue;  // blank line
    if (f.size() != header.size()) {
      throw InputError(path, fmt::format("line {}: {} fields, the header has {}", line, f.size(),
                                         header.size()));
    }
    auto get = [&](const std::string& name) -> std::string {
      const auto it = col.find(name);
      return it == col.end() ? std::string() : f[it->second];
    };
    // NaN for an absent column or an empty field.
    auto num = [&](const std::string& name) {
      return col.count(name) ? ParseDouble(get(name), path, line, name) : NAN;
    };
    auto count = [&](const std::string& name) {
      return col.count(name) ? ParseInt(get(name), path, line, name) : 0L;
    };
    BenchPoint b;
    // Whether the error metrics are ok decides whether they must be numbers.
    if (col.count("metric_ok") && get("metric_ok") != "0" && get("metric_ok") != "1") {
      throw InputError(path, fmt::format("line {}: column metric_ok: '{}' is not 0 or 1", line,
                                         get("metric_ok")));
    }
    b.metrics.ok = col.count("metric_ok")
                       ? get("metric_ok") == "1"
                       : std::isfinite(num(kErrorMetrics[kPrimaryErrorMetric].name));
    RenderedError& re = b.metrics.rendered;
    for (const BenchColumn& c : kBenchColumns) {
      switch (c.kind) {
        case BenchKind::kText:
          c.text(b) = get(c.name);
          break;
        case BenchKind::kMillis: {
          // What a file does not record reads as 0, as in a fit report: no NaN leaves the
          // reader (an empty time written back as "nan" would be refused).
          const double v = num(c.name);
          if (col.count(c.name)) RequireNonNegative(v, path, line, c.name);
          c.number(b) = std::isnan(v) ? 0 : v;
          break;
        }
        case BenchKind::kDegrees: {
          const double v = num(c.name);
          c.number(b) = std::isnan(v) ? 0 : v;
          if (c.number(b) < 0 || c.number(b) > 90) {
            throw InputError(path, fmt::format("line {}: column {}: {} is outside [0, 90]", line,
                                               c.name, c.number(b)));
          }
          break;
        }
        case BenchKind::kCount:
          c.count(b) = static_cast<std::size_t>(count(c.name));
          break;
        case BenchKind::kSmallCount: {
          const long v = count(c.name);
          if (v > std::numeric_limits<int>::max()) {
            throw InputError(path,
                             fmt::format("line {}: column {}: {} is too large", line, c.name, v));
          }
          c.small_count(b) = static_cast<int>(v);
          break;
        }
        case BenchKind::kMetricOk:
          break;  // read above
        case BenchKind::kErrorMetrics:
          // Required and >= 0 when the metrics are ok; 0 when absent or not computed.
          for (const ErrorMetricField& m : kErrorMetrics) {
            const double v = num(m.name);
            if (b.metrics.ok && col.count(m.name)) RequireNonNegative(v, path, line, m.name);
            b.metrics.*m.value = std::isnan(v) ? 0 : v;
          }
          break;
        case BenchKind::kRenderedSummary: {
          // Files written before the rendered-image metric have none of its columns; an
          // optional number (core/metrics.h) may be empty alone: not computed, read as NaN.
          re.ok = true;
          bool none = true;
          std::size_t required = 0;
          for (const RenderedSummaryField& m : kRenderedSummary) {
            re.*m.value = num(m.name);
            if (!m.required) continue;
            ++required;
            re.ok = re.ok && std::isfinite(re.*m.value);
            none = none && std::isnan(re.*m.value);
          }
          if (!re.ok && !none) {
            throw InputError(path, fmt::format("line {}: the rendered-error columns are partly "
                                               "empty (all {} or none)",
                                               line, required));
          }
          for (const RenderedSummaryField& m : kRenderedSummary) {
            if (re.ok && re.*m.value < m.min_value) {
              throw InputError(path, fmt::format("line {}: column {}: {} is below {}", line, m.name,
                                                 re.*m.value, m.min_value));
            }
            if (!re.ok) re.*m.value = m.required ? 0 : NAN;
          }
          break;
        }
        case BenchKind::kRegions:
          // Both numbers or neither, and only with the rendered summary (read before: it
          // precedes this group). The CSV does not record how many lights a region had: 1
          // marks it judged.
          for (int g = 0; g < kRenderedRegions; ++g) {
            const std::string psnr_col = RegionColumn(g, "psnr_db");
            const std::string median_col = RegionColumn(g, "median_rel_error");
            const double psnr = num(psnr_col), median = num(median_col);
            if (std::isnan(psnr) && std::isnan(median)) continue;
            if (!re.ok || !std::isfinite(psnr) || !(median >= 0) || !std::isfinite(median)) {
              throw InputError(path, fmt::format("line {}: {} and {} must both be given, with "
                                                 "the rendered-error columns, and the median >= 0",
                                                 line, psnr_col, median_col));
            }
            re.regions[static_cast<std::size_t>(g)] = {1, psnr, median};
          }
          break;
      }
    }
    points.push_back(std::move(b));
  }
  return points;
}

}  // namespace brdfit::report
