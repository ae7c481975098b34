// Reading the files `brdfit report` and `brdfit compare` are given into one report
// (report/report_model.h). Each input is classified by name and content:
//   <stem>.factor.json       a factorization (io/factor_io.h): one entry of its table's material
//   *.csv                    a bench CSV (report/bench_csv.h): bench points
//   *.png                    a preview render, embedded
//   fit reports              every fit of every material (io/fit_report.h, HDF5)
//   fit parameters .json     the same fits without times (brdfit fit --json); read only when
//                            named, not from a folder (the fit report beside it has them)
//   *.binary, table *.h5     a table: the source of θh slices for the material of its stem
//   nbrdf:NAME               a table too (NAME's network, tabulated by the caller: pipeline/)
//   a folder                 every file in it (not recursive) of the kinds above; others skipped
// A material is named after its table's file stem ("red-plastic" for red-plastic.binary).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/input_name.h"
#include "report/report_model.h"

namespace brdfit::report {

// Throws InputError naming the file when an input is missing, not a regular file or folder,
// unreadable, of no known kind, or holds a member out of its range (io/result_json.h); with
// `skipped`, such an input is left out and its error appended there instead.
ReportSources ReadReportInputs(const std::vector<std::filesystem::path>& inputs,
                               std::vector<std::string>* skipped = nullptr);

// Bench points as entries of their materials (for `brdfit compare` on two bench CSVs): one fit
// entry per point, keyed like any fit (model | loss | budget).
void AddBenchEntries(Report* report);

// One factorization sidecar as a report entry (exposed for tests). Sets *material from the
// sidecar's source.file.
Entry FactorEntry(const std::filesystem::path& sidecar, std::string* material, std::string* table);

}  // namespace brdfit::report
