// glTF 2.0 (.gltf + .bin, or .glb): one UV sphere with the exported material (export/targets.h
// GltfPbr), the provenance in asset.extras and material.extras (docs/exports.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "export/provenance.h"
#include "export/targets.h"

namespace brdfit::exports {

struct GltfFiles {
  std::string json;               // the .gltf, or the JSON chunk of a .glb
  std::vector<std::uint8_t> bin;  // the buffer: positions, normals, indices
};

// bin_uri: the .bin's file name for a .gltf; empty for a .glb (the buffer is its BIN chunk).
GltfFiles BuildGltf(const GltfPbr& g, const Provenance& p, const std::string& bin_uri);

// The binary container (glTF 2.0 §4.4): header, JSON chunk padded with spaces, BIN chunk
// padded with zeros, each to 4 bytes.
std::vector<std::uint8_t> PackGlb(const GltfFiles& f);

}  // namespace brdfit::exports
