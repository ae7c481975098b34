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

const std::vector<std::string>& BenchCsvColumns() {
  static const std::vector<std::string> columns = [] {
    std::vector<std::string> c = {"material", "table",   "model",      "loss",    "budget",
                                  "status",   "time_ms", "prepare_ms", "init_ms", "solve_ms"};
    for (const ErrorMetricField& f : kErrorMetrics) c.push_back(f.name);
    c.insert(c.end(), {"metric_ok", "metric_cells", "weighting", "cutoff_deg", "fit_cells",
                       "iterations", "message"});
    // Appended with the rendered-image metric (docs/accuracy.md); empty when not computed.
    for (const RenderedSummaryField& f : kRenderedSummary) c.push_back(f.name);
    // Appended with the metric's regions (core/rendered_regions.h); empty for a region
    // without lights and when the metric was not computed.
    for (const char* region : kRenderedRegionNames) {
      c.push_back(std::string(region) + "_psnr_db");
      c.push_back(std::string(region) + "_median_rel_error");
    }
    return c;
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
  for (const BenchPoint& b : points) {
    std::vector<std::string> fields = {
        Quote(b.material), Quote(b.table), Quote(b.model),    Quote(b.loss),  Quote(b.budget),
        Quote(b.status),   Num(b.time_ms), Num(b.prepare_ms), Num(b.init_ms), Num(b.solve_ms)};
    for (const ErrorMetricField& f : kErrorMetrics) fields.push_back(Num(b.metrics.*f.value));
    fields.insert(fields.end(),
                  {b.metrics.ok ? "1" : "0", std::to_string(b.metrics.cells),
                   Quote(b.metrics.weighting), Num(b.metrics.cutoff_deg),
                   std::to_string(b.fit_cells), std::to_string(b.iterations), Quote(b.message)});
    for (const RenderedSummaryField& f : kRenderedSummary) {
      fields.push_back(Rendered(b.metrics.rendered, b.metrics.rendered.*f.value));
    }
    for (const RenderedRegionError& g : b.metrics.rendered.regions) {
      const bool judged = b.metrics.rendered.ok && g.lights > 0;
      fields.push_back(judged ? Num(g.psnr_db) : std::string());
      fields.push_back(judged ? Num(g.median_rel_error) : std::string());
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
  for (const char* required : {"material", "model", "budget", "time_ms", "log_rmse"}) {
    if (!col.count(required)) {
      throw InputError(path, fmt::format("not a brdfit bench CSV: no column '{}'", required));
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
    auto get = [&](const char* name) -> std::string {
      const auto it = col.find(name);
      return it == col.end() ? std::string() : f[it->second];
    };
    auto num = [&](const char* name) {
      return col.count(name) ? ParseDouble(get(name), path, line, name) : NAN;
    };
    auto count = [&](const char* name) {
      return col.count(name) ? ParseInt(get(name), path, line, name) : 0L;
    };
    BenchPoint b;
    b.material = get("material");
    b.table = get("table");
    b.model = get("model");
    b.loss = get("loss");
    b.budget = get("budget");
    b.status = get("status");
    b.message = get("message");
    b.time_ms = num("time_ms");
    b.prepare_ms = num("prepare_ms");
    b.init_ms = num("init_ms");
    b.solve_ms = num("solve_ms");
    for (const ErrorMetricField& f : kErrorMetrics) b.metrics.*f.value = num(f.name);
    if (col.count("metric_ok") && get("metric_ok") != "0" && get("metric_ok") != "1") {
      throw InputError(path, fmt::format("line {}: column metric_ok: '{}' is not 0 or 1", line,
                                         get("metric_ok")));
    }
    b.metrics.ok = col.count("metric_ok")
                       ? get("metric_ok") == "1"
                       : std::isfinite(b.metrics.*kErrorMetrics[kPrimaryErrorMetric].value);
    RequireNonNegative(b.time_ms, path, line, "time_ms");
    for (const char* c : {"prepare_ms", "init_ms", "solve_ms"}) {
      if (col.count(c)) RequireNonNegative(num(c), path, line, c);
    }
    if (b.metrics.ok) {
      for (const ErrorMetricField& f : kErrorMetrics) {
        if (col.count(f.name)) RequireNonNegative(b.metrics.*f.value, path, line, f.name);
      }
    }
    // What a file does not record reads as 0, as in a fit report: no NaN leaves the reader
    // (fuzz_bench_csv: an empty error of a failed point was written back as "nan" and refused).
    for (double* v : {&b.prepare_ms, &b.init_ms, &b.solve_ms}) {
      if (std::isnan(*v)) *v = 0;
    }
    for (const ErrorMetricField& f : kErrorMetrics) {
      if (std::isnan(b.metrics.*f.value)) b.metrics.*f.value = 0;
    }
    b.metrics.cells = static_cast<std::size_t>(count("metric_cells"));
    b.metrics.weighting = get("weighting");
    b.metrics.cutoff_deg = num("cutoff_deg");
    if (std::isnan(b.metrics.cutoff_deg)) b.metrics.cutoff_deg = 0;
    if (b.metrics.cutoff_deg < 0 || b.metrics.cutoff_deg > 90) {
      throw InputError(path, fmt::format("line {}: column cutoff_deg: {} is outside [0, 90]", line,
                                         b.metrics.cutoff_deg));
    }
    b.fit_cells = static_cast<std::size_t>(count("fit_cells"));
    const long iterations = count("iterations");
    if (iterations > std::numeric_limits<int>::max()) {
      throw InputError(
          path, fmt::format("line {}: column iterations: {} is too large", line, iterations));
    }
    b.iterations = static_cast<int>(iterations);
    // Files written before the rendered-image metric have none of its columns.
    RenderedError& re = b.metrics.rendered;
    re.ok = true;
    bool none = true;
    for (const RenderedSummaryField& f : kRenderedSummary) {
      re.*f.value = num(f.name);
      re.ok = re.ok && std::isfinite(re.*f.value);
      none = none && std::isnan(re.*f.value);
    }
    if (!re.ok && !none) {
      throw InputError(path, fmt::format("line {}: the rendered-error columns are partly empty "
                                         "(all {} or none)",
                                         line, std::size(kRenderedSummary)));
    }
    for (const RenderedSummaryField& f : kRenderedSummary) {
      if (re.ok && re.*f.value < f.min_value) {
        throw InputError(path, fmt::format("line {}: column {}: {} is below {}", line, f.name,
                                           re.*f.value, f.min_value));
      }
      if (!re.ok) re.*f.value = 0;
    }
    // The regions (files written before them have none): both numbers or neither, and only
    // with the metric. The CSV does not record how many lights a region had: 1 marks it judged.
    for (int g = 0; g < kRenderedRegions; ++g) {
      const std::string name = kRenderedRegionNames[g];
      const std::string psnr_col = name + "_psnr_db", median_col = name + "_median_rel_error";
      const double psnr = num(psnr_col.c_str()), median = num(median_col.c_str());
      if (std::isnan(psnr) && std::isnan(median)) continue;
      if (!re.ok || !std::isfinite(psnr) || !(median >= 0) || !std::isfinite(median)) {
        throw InputError(path, fmt::format("line {}: {} and {} must both be given, with the "
                                           "rendered-error columns, and the median >= 0",
                                           line, psnr_col, median_col));
      }
      re.regions[static_cast<std::size_t>(g)] = {1, psnr, median};
    }
    points.push_back(std::move(b));
  }
  return points;
}

}  // namespace brdfit::report
