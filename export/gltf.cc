#include "export/gltf.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "models/geometry.h"

namespace brdfit::exports {

namespace {

using Json = nlohmann::ordered_json;

constexpr int kRings = 32;     // latitude bands
constexpr int kSegments = 64;  // longitude bands

template <class T>
void Append(std::vector<std::uint8_t>* out, T v) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // little-endian hosts only (x86-64, arm64)
  out->insert(out->end(), b, b + sizeof(T));
}

void Pad4(std::vector<std::uint8_t>* out, std::uint8_t fill) {
  while (out->size() % 4) out->push_back(fill);
}

Json Array3(const Rgb& v) {
  return Json::array({v[0], v[1], v[2]});
}

Json ProvenanceJson(const Provenance& p) {
  Json j;
  j["brdfit_version"] = p.version;
  j["source_table"] = p.source;
  j["material"] = p.material;
  j["fitted_model"] = p.model;
  j["fits"] = p.fits;
  j["fit_metrics"] = p.metrics;
  j["export"] = p.FidelityLine();
  j["masking"] =
      "height-correlated Smith V (Heitz 2014 eq. 99), as three.js, the Khronos glTF Sample "
      "Viewer and Filament evaluate glTF; Appendix B of the glTF 2.0 spec prints the separable "
      "form, under which the lobe differs towards grazing (docs/exports.md)";
  return j;
}

// A file name as a relative URI reference (glTF 2.0, section 3.3.1 "URIs"; RFC 3986, sections
// 2.1 and 2.3): every byte but the unreserved characters percent-encoded, so '#', '?', '%' or a
// space in the name stay part of the path instead of starting a fragment or a query.
std::string UriPathSegment(const std::string& name) {
  std::string out;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) || ch == '-' || ch == '.' || ch == '_' || ch == '~') {
      out += ch;
    } else {
      static const char* kHex = "0123456789ABCDEF";
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

}  // namespace

GltfFiles BuildGltf(const GltfPbr& g, const Provenance& p, const std::string& bin_uri) {
  GltfFiles f;
  // Unit UV sphere, y up: (kRings + 1) x (kSegments + 1) vertices (the seam duplicated), normals
  // equal to positions, counter-clockwise triangles seen from outside.
  const int nv = (kRings + 1) * (kSegments + 1);
  std::vector<std::uint8_t> positions, normals, indices;
  for (int i = 0; i <= kRings; ++i) {
    const double theta = kPi * i / kRings;
    for (int j = 0; j <= kSegments; ++j) {
      const double phi = 2 * kPi * j / kSegments;
      const float x = static_cast<float>(std::sin(theta) * std::sin(phi));
      const float y = static_cast<float>(std::cos(theta));
      const float z = static_cast<float>(std::sin(theta) * std::cos(phi));
      for (const float c : {x, y, z}) Append(&positions, c);
      for (const float c : {x, y, z}) Append(&normals, c);
    }
  }
  int ni = 0;
  for (int i = 0; i < kRings; ++i) {
    for (int j = 0; j < kSegments; ++j) {
      const auto a = static_cast<std::uint16_t>(i * (kSegments + 1) + j);
      const auto b = static_cast<std::uint16_t>(a + kSegments + 1);
      // Skip the degenerate triangles at the poles.
      if (i != 0) {
        for (const std::uint16_t v : {a, b, static_cast<std::uint16_t>(a + 1)}) Append(&indices, v);
        ni += 3;
      }
      if (i != kRings - 1) {
        for (const std::uint16_t v :
             {static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)}) {
          Append(&indices, v);
        }
        ni += 3;
      }
    }
  }
  f.bin = positions;
  f.bin.insert(f.bin.end(), normals.begin(), normals.end());
  f.bin.insert(f.bin.end(), indices.begin(), indices.end());
  Pad4(&f.bin, 0);

  Json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "brdfit " + p.version}};
  j["asset"]["extras"] = ProvenanceJson(p);
  Json used = Json::array();
  if (g.specular_ext) used.push_back("KHR_materials_specular");
  if (g.ior_ext) used.push_back("KHR_materials_ior");
  if (g.sheen_ext) used.push_back("KHR_materials_sheen");
  if (!used.empty()) j["extensionsUsed"] = used;
  j["scene"] = 0;
  j["scenes"] = Json::array({{{"name", p.material}, {"nodes", Json::array({0})}}});
  j["nodes"] = Json::array({{{"name", p.material + " sphere"}, {"mesh", 0}}});
  j["meshes"] =
      Json::array({{{"name", "sphere"},
                    {"primitives", Json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}},
                                                 {"indices", 2},
                                                 {"material", 0},
                                                 {"mode", 4}}})}}});
  Json mat;
  mat["name"] = p.material.empty() ? "brdfit" : p.material;
  mat["pbrMetallicRoughness"] = {
      {"baseColorFactor", Json::array({g.base_color[0], g.base_color[1], g.base_color[2], 1.0})},
      {"metallicFactor", g.metallic},
      {"roughnessFactor", g.roughness}};
  if (!used.empty()) {
    Json ext;
    if (g.specular_ext) {
      ext["KHR_materials_specular"] = {{"specularFactor", g.specular_factor},
                                       {"specularColorFactor", Array3(g.specular_color)}};
    }
    if (g.ior_ext) ext["KHR_materials_ior"] = {{"ior", g.ior}};
    if (g.sheen_ext) {
      ext["KHR_materials_sheen"] = {{"sheenColorFactor", Array3(g.sheen_color)},
                                    {"sheenRoughnessFactor", g.sheen_roughness}};
    }
    mat["extensions"] = ext;
  }
  mat["extras"] = ProvenanceJson(p);
  j["materials"] = Json::array({mat});
  const std::size_t pos_bytes = positions.size(), nrm_bytes = normals.size(),
                    idx_bytes = indices.size();
  j["buffers"] = Json::array({{{"byteLength", f.bin.size()}}});
  if (!bin_uri.empty()) j["buffers"][0]["uri"] = UriPathSegment(bin_uri);
  j["bufferViews"] = Json::array(
      {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos_bytes}, {"target", 34962}},
       {{"buffer", 0}, {"byteOffset", pos_bytes}, {"byteLength", nrm_bytes}, {"target", 34962}},
       {{"buffer", 0},
        {"byteOffset", pos_bytes + nrm_bytes},
        {"byteLength", idx_bytes},
        {"target", 34963}}});
  j["accessors"] = Json::array(
      {{{"bufferView", 0},
        {"componentType", 5126},
        {"count", nv},
        {"type", "VEC3"},
        {"min", Json::array({-1.0, -1.0, -1.0})},
        {"max", Json::array({1.0, 1.0, 1.0})}},
       {{"bufferView", 1}, {"componentType", 5126}, {"count", nv}, {"type", "VEC3"}},
       {{"bufferView", 2}, {"componentType", 5123}, {"count", ni}, {"type", "SCALAR"}}});
  f.json = j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
  return f;
}

std::vector<std::uint8_t> PackGlb(const GltfFiles& f) {
  std::vector<std::uint8_t> json(f.json.begin(), f.json.end());
  Pad4(&json, ' ');
  std::vector<std::uint8_t> bin = f.bin;
  Pad4(&bin, 0);
  std::vector<std::uint8_t> out;
  const auto total = static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size());
  Append(&out, std::uint32_t{0x46546C67});  // "glTF"
  Append(&out, std::uint32_t{2});
  Append(&out, total);
  Append(&out, static_cast<std::uint32_t>(json.size()));
  Append(&out, std::uint32_t{0x4E4F534A});  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  Append(&out, static_cast<std::uint32_t>(bin.size()));
  Append(&out, std::uint32_t{0x004E4942});  // "BIN\0"
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

}  // namespace brdfit::exports
