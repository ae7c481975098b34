// `brdfit fit --target T`: the models a target renderer evaluates exactly (so that fitting them
// makes an exact export), and what the export of a given fit to T approximates
// (docs/exports.md, docs/cli.md "fit").
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "export/targets.h"
#include "export/write_export.h"

namespace brdfit::exports {

struct FitTarget {
  const char* name;                 // "gltf", ...
  Format format;                    // the export it is checked with
  // fitted when --model is not given, the first the one-lobe form; empty: any (threejs)
  std::vector<std::string> models;
  const char* note;                 // what the target is, for --help and messages
};

// "gltf" | "threejs" | "blender" | "mitsuba" | "pbrt"; throws InputError listing them.
const FitTarget& FitTargetOf(const std::string& name);
// The target an export format is checked against (glb and gltf: "gltf"); nullptr for threejs,
// which renders every model exactly and fits nothing of its own.
const FitTarget* FitTargetForFormat(Format format);
// "gltf, threejs, blender, mitsuba, pbrt".
std::string FitTargetNames();

// What exporting `fit` to `target` approximates (the exporters' own check): empty when exact;
// a model the target cannot take gives one entry naming the exportable models.
Fidelity ExportFidelity(const FitResult& fit, const FitTarget& target);

}  // namespace brdfit::exports
