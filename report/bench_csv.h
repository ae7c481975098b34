// The CSV of `brdfit bench`: one row per (table, model, loss, budget) fit, run time against
// error (docs/cli.md lists the columns). RFC 4180 quoting; a header row names the columns;
// readers find columns by name, so columns may be added later without breaking old files.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "report/report_model.h"

namespace brdfit::report {

// Column names, in the order WriteBenchCsv writes them.
const std::vector<std::string>& BenchCsvColumns();

std::string BenchCsvText(const std::vector<BenchPoint>& points);
void WriteBenchCsv(const std::filesystem::path& path, const std::vector<BenchPoint>& points);

// Throws InputError naming the file and line on a malformed file or a missing column.
std::vector<BenchPoint> ReadBenchCsv(const std::filesystem::path& path);

// RFC 4180 line splitting (exposed for tests): fields of one record; quoted fields may hold
// commas, doubled quotes and newlines. `text` is the whole file; `pos` advances past the
// record. Throws std::invalid_argument on an unterminated quote.
std::vector<std::string> SplitCsvRecord(const std::string& text, std::size_t* pos);

}  // namespace brdfit::report
