// The exported files, read back and evaluated with each target's documented BSDF, against
// brdfit's own model at random directions (docs/exports.md):
//   glTF 2.0 Appendix B "BRDF implementation" (diffuse_brdf, specular_brdf = V D, metal_brdf,
//     fresnel_mix) with KHR_materials_specular (fresnel_mix(f0_color, weight, ...), f0_color =
//     min(((ior - 1)/(ior + 1))^2 specularColor, 1)) and KHR_materials_ior; V in its
//     height-correlated form (the Khronos glTF Sample Viewer's and three.js's V_GGX;
//     Heitz 2014 eq. 99) and in the separable form Appendix B prints;
//   Mitsuba 3 plugin docs: blendbsdf (1 - weight) bsdf_0 + weight bsdf_1, diffuse R / pi,
//     roughconductor = F D G / (4 cos_i cos_o) with G = G1(wi) G1(wo) (Smith, uncorrelated),
//     material="none" (eta 0 + 1i: |F| = 1), times specular_reflectance; principled
//     (src/bsdfs/principled.cpp eval: the diffuse base_color / pi (f_diff + f_retro), the
//     specular lobe weighted by the dielectric Fresnel of eta = 2 / (1 - sqrt(0.08 specular)) - 1,
//     0 at specular 0);
//   pbrt-v4 (Physically Based Rendering 4th ed. §9.3 TrowbridgeReitzDistribution, G = 1 / (1 +
//     Lambda(wo) + Lambda(wi)); §9.4 ConductorBxDF, FrComplex; materials "conductor" with
//     reflectance r: eta = 1, k = 2 sqrt(r) / sqrt(1 - r), r clamped to [0, 0.9999];
//     "mix": materials[1] with probability amount; "diffuse" R / pi);
//   Blender 3.4 Cycles (intern/cycles/kernel/closure: bsdf_diffuse.h Lambert; bsdf_microfacet.h
//     GGX D G1(wi) G1(wo) / (4 cos_i cos_o) with alpha = roughness^2, and the Principled
//     BSDF's interpolate_fresnel_color; bsdf_principled_diffuse.h Burley's diffuse;
//     svm_closure.h: Principled cspec0, IOR from Specular, metallic-weighted diffuse).
// Exact exports must agree to rounding; approximate ones must say so in the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "export/write_export.h"
#include "io/fit_params_json.h"
#include "models/geometry.h"
#include "models/registry.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using exports::Format;
using Rgb = std::array<double, 3>;

// ---- the targets' formulas, written from their documentation (not from brdfit's models)

// GGX / Trowbridge-Reitz NDF, Walter et al. 2007 eq. 33; Lambda, Heitz 2014 eq. 72.
double DGgx(double a, double cos_h) {
  const double c2 = cos_h * cos_h, t = c2 * (a * a - 1) + 1;
  return a * a / (kPi * t * t);
}
double Lambda(double a, double cos_v) {
  const double c2 = cos_v * cos_v, tan2 = (1 - c2) / c2;
  return (-1 + std::sqrt(1 + a * a * tan2)) / 2;
}
double GHeightCorrelated(double a, double ci, double co) {
  return 1 / (1 + Lambda(a, ci) + Lambda(a, co));
}
double GSeparable(double a, double ci, double co) {
  return 1 / ((1 + Lambda(a, ci)) * (1 + Lambda(a, co)));
}

struct Dirs {
  Vec3 wi, wo, h;
  double ci, co, ch, cd;
};
Dirs MakeDirs(const Vec3& wi, const Vec3& wo) {
  Dirs d{wi, wo, Normalize(wi + wo), wi.z, wo.z, 0, 0};
  d.ch = d.h.z;
  d.cd = Dot(wo, d.h);
  return d;
}

// A GGX microfacet lobe without Fresnel: D G / (4 cos_i cos_o), G height-correlated or
// separable (Walter 2007 eq. 20 with F = 1).
double GgxLobe(double a, const Dirs& d, bool height_correlated) {
  const double g = height_correlated ? GHeightCorrelated(a, d.ci, d.co) : GSeparable(a, d.ci, d.co);
  return DGgx(a, d.ch) * g / (4 * d.ci * d.co);
}

Rgb Array(const nlohmann::json& j, std::size_t n = 3) {
  Rgb v{};
  for (std::size_t c = 0; c < 3 && c < n; ++c) v[c] = j.at(c).get<double>();
  return v;
}

// glTF 2.0 Appendix B + KHR_materials_specular + KHR_materials_ior.
Rgb GltfEval(const nlohmann::json& mat, const Dirs& d, bool height_correlated) {
  const auto& pbr = mat.at("pbrMetallicRoughness");
  const Rgb base = Array(pbr.at("baseColorFactor"));
  const double metallic = pbr.value("metallicFactor", 1.0);
  const double rough = pbr.value("roughnessFactor", 1.0);
  const double a = rough * rough;
  double w = 1, ior = 1.5;
  Rgb spec_color{1, 1, 1};
  if (mat.contains("extensions")) {
    const auto& ext = mat["extensions"];
    if (ext.contains("KHR_materials_specular")) {
      w = ext["KHR_materials_specular"].value("specularFactor", 1.0);
      if (ext["KHR_materials_specular"].contains("specularColorFactor")) {
        spec_color = Array(ext["KHR_materials_specular"]["specularColorFactor"]);
      }
    }
    if (ext.contains("KHR_materials_ior")) ior = ext["KHR_materials_ior"].value("ior", 1.5);
  }
  const double g = height_correlated ? GHeightCorrelated(a, d.ci, d.co) : GSeparable(a, d.ci, d.co);
  const double specular_brdf = g / (4 * d.ci * d.co) * DGgx(a, d.ch);
  const double s5 = std::pow(1 - std::abs(d.cd), 5);
  const double f0_ior = std::pow((ior - 1) / (ior + 1), 2);
  Rgb fr{};
  for (int c = 0; c < 3; ++c) {
    const double f0 = std::min(f0_ior * spec_color[c], 1.0);
    fr[c] = f0 + (1 - f0) * s5;
  }
  const double max_fr = std::max({fr[0], fr[1], fr[2]});
  Rgb out{};
  for (int c = 0; c < 3; ++c) {
    const double dielectric = (1 - w * max_fr) * base[c] / kPi + w * fr[c] * specular_brdf;
    const double metal = specular_brdf * (base[c] + (1 - base[c]) * s5);
    out[c] = (1 - metallic) * dielectric + metallic * metal;
  }
  return out;
}

// The material of an exported .gltf or .glb (the JSON chunk of the container).
nlohmann::json GltfMaterial(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string json = bytes;
  if (bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0) {
    std::uint32_t total = 0, len = 0;
    std::memcpy(&total, bytes.data() + 8, 4);
    std::memcpy(&len, bytes.data() + 12, 4);
    EXPECT_EQ(total, bytes.size());
    EXPECT_EQ(bytes.compare(16, 4, "JSON"), 0);
    json = bytes.substr(20, len);
  }
  return nlohmann::json::parse(json).at("materials").at(0);
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Mitsuba 3: the values of <TYPE name="NAME" value="..."/> inside the named plugin's element.
std::string MitsubaValue(const std::string& xml, const std::string& plugin, const std::string& tag,
                         const std::string& name) {
  const std::size_t at = xml.find("<bsdf type=\"" + plugin + "\"");
  EXPECT_NE(at, std::string::npos) << plugin;
  const std::string key = "<" + tag + " name=\"" + name + "\" value=\"";
  const std::size_t k = at == std::string::npos ? at : xml.find(key, at);
  EXPECT_NE(k, std::string::npos) << plugin << " " << name;
  if (k == std::string::npos) return "";
  const std::size_t begin = k + key.size(), end = xml.find('"', begin);
  return xml.substr(begin, end - begin);
}
Rgb ParseRgb(const std::string& s) {
  Rgb v{};
  std::sscanf(s.c_str(), "%lf, %lf, %lf", &v[0], &v[1], &v[2]);
  return v;
}

// Every roughconductor's (alpha, specular_reflectance), in the order of the file.
std::vector<std::pair<double, Rgb>> MitsubaConductors(const std::string& xml) {
  std::vector<std::pair<double, Rgb>> out;
  for (std::size_t at = xml.find("<bsdf type=\"roughconductor\""); at != std::string::npos;
       at = xml.find("<bsdf type=\"roughconductor\"", at + 1)) {
    const std::string rest = xml.substr(at);
    EXPECT_EQ(MitsubaValue(rest, "roughconductor", "string", "distribution"), "ggx");
    EXPECT_EQ(MitsubaValue(rest, "roughconductor", "string", "material"), "none");
    out.emplace_back(std::stod(MitsubaValue(rest, "roughconductor", "float", "alpha")),
                     ParseRgb(MitsubaValue(rest, "roughconductor", "rgb", "specular_reflectance")));
  }
  return out;
}

// Mitsuba 3's principled BSDF with metallic 0, no transmission, clearcoat, sheen or flatness
// (src/bsdfs/principled.cpp, eval): base_color / pi ((1 - Fi/2)(1 - Fo/2) + Rr (Fo + Fi + Fo Fi
// (Rr - 1))), F = (1 - cos)^5, Rr = 2 roughness (h.wo)^2, plus its GGX lobe weighted by the
// dielectric Fresnel of eta = 2 / (1 - sqrt(0.08 specular)) - 1, which is 0 at eta 1: the test
// requires specular 0 rather than evaluating that lobe.
double MitsubaPrincipledDiffuse(const std::string& xml, const Dirs& d) {
  EXPECT_EQ(std::stod(MitsubaValue(xml, "principled", "float", "specular")), 0.0);
  EXPECT_EQ(std::stod(MitsubaValue(xml, "principled", "float", "metallic")), 0.0);
  const double roughness = std::stod(MitsubaValue(xml, "principled", "float", "roughness"));
  const double fi = std::pow(1 - d.ci, 5), fo = std::pow(1 - d.co, 5);
  const double rr = 2 * roughness * d.cd * d.cd;
  return ((1 - 0.5 * fi) * (1 - 0.5 * fo) + rr * (fo + fi + fo * fi * (rr - 1))) / kPi;
}

// blendbsdf(w) of a body, diffuse(R) or principled(base_color R), and either one
// roughconductor or a nested blendbsdf(v) of two: (1 - w) R body + w S lobe, or
// (1 - w) R body + w ((1 - v) S1 lobe1 + v S2 lobe2).
Rgb MitsubaEval(const std::string& xml, const Dirs& d) {
  const double w = std::stod(MitsubaValue(xml, "blendbsdf", "float", "weight"));
  const bool principled = xml.find("<bsdf type=\"principled\"") != std::string::npos;
  const Rgb r = principled ? ParseRgb(MitsubaValue(xml, "principled", "rgb", "base_color"))
                           : ParseRgb(MitsubaValue(xml, "diffuse", "rgb", "reflectance"));
  const double body = principled ? MitsubaPrincipledDiffuse(xml, d) : 1 / kPi;
  const auto conductors = MitsubaConductors(xml);
  EXPECT_TRUE(conductors.size() == 1 || conductors.size() == 2) << conductors.size();
  std::vector<double> share = {1.0};
  if (conductors.size() == 2) {
    const std::size_t inner = xml.find("<bsdf type=\"blendbsdf\"", xml.find("</bsdf>"));
    EXPECT_NE(inner, std::string::npos) << "the nested blendbsdf";
    const double v = std::stod(MitsubaValue(xml.substr(inner), "blendbsdf", "float", "weight"));
    share = {1 - v, v};
  }
  Rgb out{};
  for (int c = 0; c < 3; ++c) out[c] = (1 - w) * r[c] * body;
  for (std::size_t i = 0; i < conductors.size() && i < share.size(); ++i) {
    const auto& [a, s] = conductors[i];
    const double lobe = GgxLobe(a, d, false);
    for (int c = 0; c < 3; ++c) out[c] += w * share[i] * s[c] * lobe;  // |F| = 1
  }
  return out;
}

// pbrt-v4 scene text as tokens: quoted strings, brackets, bare words; '#' comments dropped.
std::vector<std::string> PbrtTokens(const std::string& text) {
  std::vector<std::string> t;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '"') {
      const std::size_t end = text.find('"', i + 1);
      EXPECT_NE(end, std::string::npos) << "unterminated string";
      t.push_back(text.substr(i, end - i + 1));
      i = end + 1;
    } else if (c == '[' || c == ']') {
      t.emplace_back(1, c);
      ++i;
    } else {
      std::size_t j = i;
      while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j])) &&
             text[j] != '[' && text[j] != ']' && text[j] != '"') {
        ++j;
      }
      t.push_back(text.substr(i, j - i));
      i = j;
    }
  }
  return t;
}

using PbrtParams = std::map<std::string, std::vector<std::string>>;  // "float amount" -> values
std::map<std::string, PbrtParams> PbrtNamedMaterials(const std::string& text) {
  const auto t = PbrtTokens(text);
  std::map<std::string, PbrtParams> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] != "MakeNamedMaterial") continue;
    const std::string& quoted = t.at(i + 1);
    PbrtParams& p = out[quoted.substr(1, quoted.size() - 2)];
    std::size_t j = i + 2;
    while (j < t.size() && t[j].front() == '"') {
      const std::string key = t[j].substr(1, t[j].size() - 2);
      ++j;
      EXPECT_EQ(t.at(j), "[") << key;
      for (++j; j < t.size() && t[j] != "]"; ++j) p[key].push_back(t[j]);
      ++j;
    }
  }
  return out;
}
double Num(const PbrtParams& p, const std::string& key, std::size_t i = 0) {
  return std::stod(p.at(key).at(i));
}
Rgb Num3(const PbrtParams& p, const std::string& key) {
  return {Num(p, key, 0), Num(p, key, 1), Num(p, key, 2)};
}

// pbrt-v4 FrComplex (PBR 4th ed. eq. 9.x): Fresnel reflectance of a conductor, eta + i k.
double FrComplex(double cos_i, std::complex<double> eta) {
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const std::complex<double> sin2_i = 1 - cos_i * cos_i, sin2_t = sin2_i / (eta * eta);
  const std::complex<double> cos_t = std::sqrt(1.0 - sin2_t);
  const std::complex<double> r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const std::complex<double> r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return (std::norm(r_parl) + std::norm(r_perp)) / 2;
}

// conductor(reflectance, roughness) as pbrt-v4 evaluates it: F_r D G / (4 cos_i cos_o), G
// height-correlated, F the Fresnel of eta = 1, k = 2 sqrt(r) / sqrt(1 - r), r <= 0.9999.
Rgb PbrtConductor(const PbrtParams& cond, const Dirs& d) {
  EXPECT_EQ(cond.at("string type").at(0), "\"conductor\"");
  EXPECT_EQ(cond.at("bool remaproughness").at(0), "false");
  const Rgb refl = Num3(cond, "rgb reflectance");
  const double a = Num(cond, "float roughness");
  const double lobe = GgxLobe(a, d, true);
  Rgb out{};
  for (int c = 0; c < 3; ++c) {
    const double rc = std::clamp(refl[c], 0.0, 0.9999);
    const double k = 2 * std::sqrt(rc) / std::sqrt(1 - rc);
    out[c] = FrComplex(std::abs(d.cd), {1.0, k}) * lobe;
  }
  return out;
}

// mix(amount a) of brdfit-diffuse and brdfit-specular; brdfit-specular a conductor, or a
// mix(v) of brdfit-specular-1 and -2 (pbrt-v4 picks materials[1] with probability amount).
Rgb PbrtEval(const std::string& text, const Dirs& d) {
  const auto mats = PbrtNamedMaterials(text);
  const PbrtParams& mix = mats.at("brdfit-material");
  EXPECT_EQ(mix.at("string type").at(0), "\"mix\"");
  EXPECT_EQ(mix.at("string materials").at(0), "\"brdfit-diffuse\"");
  EXPECT_EQ(mix.at("string materials").at(1), "\"brdfit-specular\"");
  const PbrtParams& diff = mats.at("brdfit-diffuse");
  const PbrtParams& spec = mats.at("brdfit-specular");
  Rgb lobes{};
  if (spec.at("string type").at(0) == "\"mix\"") {
    EXPECT_EQ(spec.at("string materials").at(0), "\"brdfit-specular-1\"");
    EXPECT_EQ(spec.at("string materials").at(1), "\"brdfit-specular-2\"");
    const double v = Num(spec, "float amount");
    const Rgb l1 = PbrtConductor(mats.at("brdfit-specular-1"), d);
    const Rgb l2 = PbrtConductor(mats.at("brdfit-specular-2"), d);
    for (int c = 0; c < 3; ++c) lobes[c] = (1 - v) * l1[c] + v * l2[c];
  } else {
    lobes = PbrtConductor(spec, d);
  }
  const double amount = Num(mix, "float amount");
  const Rgb r = Num3(diff, "rgb reflectance");
  Rgb out{};
  for (int c = 0; c < 3; ++c) out[c] = (1 - amount) * r[c] / kPi + amount * lobes[c];
  return out;
}

// Blender script constants: `"key": (r, g, b)` or `"key": x` inside the line `NAME = {...}`.
double PyNumber(const std::string& py, const std::string& dict, const std::string& key) {
  const std::size_t d = py.find("\n" + dict + " = {");
  EXPECT_NE(d, std::string::npos) << dict;
  const std::size_t k = py.find("\"" + key + "\": ", d);
  EXPECT_NE(k, std::string::npos) << key;
  return std::stod(py.substr(k + key.size() + 4));
}
Rgb PyTuple(const std::string& py, const std::string& dict, const std::string& key) {
  const std::size_t d = py.find("\n" + dict + " = {");
  const std::size_t k = py.find("\"" + key + "\": (", d);
  EXPECT_NE(k, std::string::npos) << key;
  Rgb v{};
  std::sscanf(py.c_str() + k + key.size() + 5, "%lf, %lf, %lf", &v[0], &v[1], &v[2]);
  return v;
}

// Cycles' fresnel_dielectric_cos: unpolarized dielectric Fresnel (Walter 2007 eq. 22).
double FresnelDielectric(double c, double eta) {
  c = std::abs(c);
  double g = eta * eta - 1 + c * c;
  if (g <= 0) return 1;
  g = std::sqrt(g);
  const double a = (g - c) / (g + c), b = (c * (g + c) - 1) / (c * (g - c) + 1);
  return 0.5 * a * a * (1 + b * b);
}

// The script's node tree: the body + Glossy BSDF (GGX), Cycles 3.4.
// The body: Diffuse BSDF with Roughness sigma (Cycles 3.4 bsdf_oren_nayar.h: a = 1 / (pi +
// (3 pi - 4) / 6 sigma), b = sigma a, t = l.v - nl nv, t /= max(nl, nv) when t > 0, value
// a + b t; Lambert at sigma 0 as bsdf_diffuse.h) or Principled BSDF with Specular 0 and
// Metallic 0 (bsdf_principled_diffuse.h, PRINCIPLED_DIFFUSE_FULL:
// (1 - FV/2)(1 - FL/2) + RR (FL + FV + FL FV (RR - 1)), RR = r (1 + l.v), over pi).
double BlenderBody(const std::string& py, const Dirs& d) {
  const double r = PyNumber(py, "EXACT", "body_roughness");
  if (py.find("\"body\": \"burley-2012\"") != std::string::npos) {
    auto schlick = [](double c) { return std::pow(std::clamp(1 - c, 0.0, 1.0), 5); };
    const double fl = schlick(d.ci), fv = schlick(d.co), rr = r * (1 + Dot(d.wi, d.wo));
    return ((1 - 0.5 * fv) * (1 - 0.5 * fl) + rr * (fl + fv + fl * fv * (rr - 1))) / kPi;
  }
  if (r == 0) return 1 / kPi;
  const double sigma = std::clamp(r, 0.0, 1.0);
  const double a = 1 / (kPi + (3 * kPi - 4) / 6 * sigma), b = sigma * a;
  double t = Dot(d.wi, d.wo) - d.ci * d.co;
  if (t > 0) t /= std::max(d.ci, d.co);
  return a + b * t;
}

Rgb BlenderExactEval(const std::string& py, const Dirs& d) {
  const Rgb kd = PyTuple(py, "EXACT", "diffuse_color"), ks = PyTuple(py, "EXACT", "glossy_color");
  const double r = PyNumber(py, "EXACT", "roughness"), a = r * r;
  const double lobe = GgxLobe(a, d, false), body = BlenderBody(py, d);
  Rgb out{};
  for (int c = 0; c < 3; ++c) out[c] = kd[c] * body + ks[c] * lobe;
  if (py.find("\"second_glossy_color\": (") != std::string::npos) {
    // + a second Glossy BSDF (GGX), added.
    const Rgb ks2 = PyTuple(py, "EXACT", "second_glossy_color");
    const double r2 = PyNumber(py, "EXACT", "second_roughness"), a2 = r2 * r2;
    const double lobe2 = GgxLobe(a2, d, false);
    for (int c = 0; c < 3; ++c) out[c] += ks2[c] * lobe2;
  }
  return out;
}

// The script's Principled BSDF as Cycles 3.4 evaluates it (no subsurface, sheen, clearcoat,
// transmission): (1 - m) base / pi Burley + F D G1 G1 / (4 cos_i cos_o).
Rgb BlenderPrincipledEval(const std::string& py, const Dirs& d) {
  const Rgb base = PyTuple(py, "PRINCIPLED", "base_color");
  const double m = PyNumber(py, "PRINCIPLED", "metallic");
  const double r = PyNumber(py, "PRINCIPLED", "roughness"), a = r * r;
  const double spec = PyNumber(py, "PRINCIPLED", "specular");
  const double tint = PyNumber(py, "PRINCIPLED", "specular_tint");
  const double lum = 0.3 * base[0] + 0.6 * base[1] + 0.1 * base[2];
  const double ior = 2 / (1 - std::sqrt(0.08 * spec)) - 1;
  const double f0 = FresnelDielectric(1, ior);
  const double fh = (FresnelDielectric(d.cd, ior) - f0) / (1 - f0);
  auto schlick = [](double c) { return std::pow(std::clamp(1 - c, 0.0, 1.0), 5); };
  const double fl = schlick(d.ci), fv = schlick(d.co);
  const double rr = r * (1 + Dot(d.wi, d.wo));
  const double burley = (1 - 0.5 * fv) * (1 - 0.5 * fl) + rr * (fl + fv + fl * fv * (rr - 1));
  const double lobe = GgxLobe(a, d, false);
  Rgb out{};
  for (int c = 0; c < 3; ++c) {
    const double ctint = lum > 0 ? base[c] / lum : 1;
    const double cspec0 = spec * 0.08 * ((1 - tint) + ctint * tint) * (1 - m) + base[c] * m;
    const double fresnel = cspec0 * (1 - fh) + fh;
    out[c] = (1 - m) * base[c] / kPi * burley + fresnel * lobe;
  }
  return out;
}

// ---- brdfit's side

FitReportEntry Entry(const std::string& model, const std::vector<double>& params) {
  const ModelInfo* m = FindModel(model);
  EXPECT_NE(m, nullptr) << model;
  FitReportEntry e;
  e.source = "synthetic";
  e.material = "test-" + model;
  e.result.model = model;
  e.result.param_names = m->param_names;
  e.result.params = params;
  e.result.at_bound.assign(params.size(), false);
  e.result.status = FitStatus::kConverged;
  return e;
}

Rgb Model(const FitReportEntry& e, const Dirs& d) {
  Rgb out{};
  FindModel(e.result.model)->eval(e.result.params.data(), MakeGeometry(d.wi, d.wo), out.data());
  return out;
}

Vec3 RandomDir(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double z = 0.05 + 0.95 * u(rng), phi = 2 * kPi * u(rng), s = std::sqrt(1 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// Max over random direction pairs and channels of |target - model| / (model + 1e-3 max model).
template <class Eval>
double MaxRelError(const FitReportEntry& e, Eval target, int n = 2000) {
  std::mt19937_64 rng(15);
  double worst = 0;
  for (int k = 0; k < n; ++k) {
    const Dirs d = MakeDirs(RandomDir(rng), RandomDir(rng));
    const Rgb m = Model(e, d), t = target(d);
    const double scale = std::max({m[0], m[1], m[2]});
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(t[c]));
      worst = std::max(worst, std::abs(t[c] - m[c]) / (m[c] + 1e-3 * scale));
    }
  }
  return worst;
}

fs::path Export(const ScratchDir& dir, const FitReportEntry& e, Format f, const std::string& name,
                bool* exact) {
  const fs::path out = dir.path() / name;
  const auto r = exports::WriteExport(e, "fits.json", f, out);
  *exact = r.fidelity.Exact();
  const std::string text = f == Format::kGlb ? "" : ReadText(out);
  if (f != Format::kGlb) {
    // A Blender script also states its (always approximate) Principled material, after.
    const std::string own = text.substr(0, text.find("# material brdfit-principled"));
    EXPECT_EQ(own.find("approximate") == std::string::npos, *exact) << name;
    EXPECT_NE(text.find("brdfit 0.1.0"), std::string::npos) << name;
    EXPECT_NE(text.find("synthetic"), std::string::npos) << name << ": the source table";
  }
  return out;
}

// Lambert + height-correlated GGX with a grey ks: exact in glTF (as the Sample Viewer and
// three.js evaluate V) and in pbrt-v4 (up to its 0.9999 reflectance clamp: 1e-3).
TEST(ExportFormulas, GreyLambertGgxHcIsExactInGltfAndPbrt) {
  ScratchDir dir;
  const auto e = Entry("lambert+ggx-hc", {0.30, 0.20, 0.10, 0.25, 0.25, 0.25, 0.15});
  bool exact = false;
  for (const Format f : {Format::kGltf, Format::kGlb}) {
    const fs::path p = Export(dir, e, f, f == Format::kGlb ? "m.glb" : "m.gltf", &exact);
    EXPECT_TRUE(exact);
    const auto mat = GltfMaterial(p);
    EXPECT_NEAR(mat["pbrMetallicRoughness"]["roughnessFactor"].get<double>(), std::sqrt(0.15),
                1e-15);
    EXPECT_LT(MaxRelError(e, [&](const Dirs& d) { return GltfEval(mat, d, true); }), 1e-12);
    // Appendix B's printed (separable) V differs: the reason docs/exports.md names the viewers.
    EXPECT_GT(MaxRelError(e, [&](const Dirs& d) { return GltfEval(mat, d, false); }), 1e-3);
  }
  const std::string pbrt = ReadText(Export(dir, e, Format::kPbrt, "m.pbrt", &exact));
  EXPECT_TRUE(exact);
  // pbrt clamps the reflectance to 0.9999 (k = 200): F dips by up to 4.3e-4 near grazing.
  EXPECT_LT(MaxRelError(e, [&](const Dirs& d) { return PbrtEval(pbrt, d); }), 1e-3);
}

// Lambert + separable GGX, any RGB ks: exact in Mitsuba 3.
TEST(ExportFormulas, LambertGgxIsExactInMitsuba) {
  ScratchDir dir;
  const auto e = Entry("lambert+ggx", {0.05, 0.10, 0.30, 0.60, 0.35, 0.10, 0.08});
  bool exact = false;
  const std::string xml = ReadText(Export(dir, e, Format::kMitsuba, "m.xml", &exact));
  EXPECT_TRUE(exact);
  EXPECT_LT(MaxRelError(e, [&](const Dirs& d) { return MitsubaEval(xml, d); }), 1e-7);
}

// Lambert + separable GGX: exact in Blender's Diffuse + Glossy node tree; the Principled BSDF
// of the same script matches at normal incidence only (docs/exports.md, "Blender").
TEST(ExportFormulas, LambertGgxIsExactInBlenderAndPrincipledAtNormalIncidence) {
  ScratchDir dir;
  bool exact = false;
  const Dirs n = MakeDirs({0, 0, 1}, {0, 0, 1});
  // grey ks: Principled metallic 0, specular = ks / 0.08; coloured ks over no diffuse:
  // metallic 1, base colour = ks.
  for (const auto& params : {std::vector<double>{0.30, 0.20, 0.10, 0.04, 0.04, 0.04, 0.08},
                             std::vector<double>{0, 0, 0, 0.60, 0.35, 0.10, 0.2}}) {
    const auto e = Entry("lambert+ggx", params);
    const std::string py = ReadText(Export(dir, e, Format::kBlender, "m.py", &exact));
    EXPECT_TRUE(exact);
    EXPECT_NEAR(PyNumber(py, "EXACT", "roughness"), std::sqrt(params[6]), 1e-9);
    EXPECT_LT(MaxRelError(e, [&](const Dirs& d) { return BlenderExactEval(py, d); }), 1e-7);
    EXPECT_NE(py.find("brdfit-principled (not on the sphere; --material principled): "
                      "approximate"),
              std::string::npos);
    const Rgb t = BlenderPrincipledEval(py, n), m = Model(e, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], m[c], 1e-7 * m[c]) << c;
    EXPECT_GT(MaxRelError(e, [&](const Dirs& d) { return BlenderPrincipledEval(py, d); }), 1e-2);
  }
  // Height-correlated masking is not Cycles 3.4's: approximate, and it differs.
  const auto hc = Entry("lambert+ggx-hc", {0.3, 0.2, 0.1, 0.3, 0.3, 0.3, 0.3});
  const std::string py = ReadText(Export(dir, hc, Format::kBlender, "h.py", &exact));
  EXPECT_FALSE(exact);
  EXPECT_GT(MaxRelError(hc, [&](const Dirs& d) { return BlenderExactEval(py, d); }), 1e-3);
}

// What a target cannot express is said, and is really not what the target evaluates.
TEST(ExportFormulas, ApproximateExportsSaySoAndDiffer) {
  ScratchDir dir;
  bool exact = true;
  {
    // A coloured ks in glTF: exact at normal incidence, not at grazing.
    const auto e = Entry("lambert+ggx-hc", {0.05, 0.10, 0.30, 0.60, 0.35, 0.10, 0.2});
    const auto mat = GltfMaterial(Export(dir, e, Format::kGltf, "c.gltf", &exact));
    EXPECT_FALSE(exact);
    const Dirs n = MakeDirs({0, 0, 1}, {0, 0, 1});
    const Rgb t = GltfEval(mat, n, true), m = Model(e, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], m[c], 1e-12 * m[c]);
    EXPECT_GT(MaxRelError(e, [&](const Dirs& d) { return GltfEval(mat, d, true); }), 1e-3);
    const std::string pbrt = ReadText(Export(dir, e, Format::kPbrt, "c.pbrt", &exact));
    EXPECT_FALSE(exact);
    const Rgb tp = PbrtEval(pbrt, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(tp[c], m[c], 2e-4 * m[c]);
  }
  {
    // Separable masking in glTF and pbrt, height-correlated in Mitsuba.
    const auto sep = Entry("lambert+ggx", {0.3, 0.2, 0.1, 0.3, 0.3, 0.3, 0.3});
    const auto mat = GltfMaterial(Export(dir, sep, Format::kGlb, "s.glb", &exact));
    EXPECT_FALSE(exact);
    EXPECT_GT(MaxRelError(sep, [&](const Dirs& d) { return GltfEval(mat, d, true); }), 1e-3);
    const auto hc = Entry("lambert+ggx-hc", {0.3, 0.2, 0.1, 0.3, 0.3, 0.3, 0.3});
    const std::string xml = ReadText(Export(dir, hc, Format::kMitsuba, "h.xml", &exact));
    EXPECT_FALSE(exact);
    EXPECT_GT(MaxRelError(hc, [&](const Dirs& d) { return MitsubaEval(xml, d); }), 1e-3);
  }
  {
    // ue4 in glTF: its own parameters, but glTF's G and (1 - F) diffuse are not ue4's.
    const auto e = Entry("ue4", {0.8, 0.3, 0.1, 0.4, 0.05});
    const auto mat = GltfMaterial(Export(dir, e, Format::kGltf, "u.gltf", &exact));
    EXPECT_FALSE(exact);
    EXPECT_NEAR(mat["pbrMetallicRoughness"]["metallicFactor"].get<double>(), 0.4, 1e-15);
    const double err = MaxRelError(e, [&](const Dirs& d) { return GltfEval(mat, d, true); });
    EXPECT_GT(err, 1e-3);
    EXPECT_LT(err, 10.0);
  }
}

// KHR_materials_sheen's sheen BRDF (the extension's README, "Sheen BRDF"): sheenColor D V,
// D the Charlie distribution (2 + 1/a) sin(th_h)^(1/a) / (2 pi) with a = sheenRoughness^2, V
// Ashikhmin's / Neubelt's 1 / (4 (cos_i + cos_o - cos_i cos_o)) (the cheaper visibility the
// README allows, the one three.js evaluates). The layer below is dimmed by the albedo scaling;
// with no base layer (base 0, no specular) it is the sheen alone.
Rgb GltfSheenEval(const nlohmann::json& mat, const Dirs& d) {
  const auto& sh = mat.at("extensions").at("KHR_materials_sheen");
  const Rgb colour = Array(sh.at("sheenColorFactor"));
  const double r = sh.at("sheenRoughnessFactor").get<double>(), a = r * r;
  const double sin_h = std::sqrt(std::max(0.0, 1 - d.ch * d.ch));
  const double dist = (2 + 1 / a) * std::pow(sin_h, 1 / a) / (2 * kPi);
  const double v = 1 / (4 * (d.ci + d.co - d.ci * d.co));
  return {colour[0] * dist * v, colour[1] * dist * v, colour[2] * dist * v};
}

// lambert+ggx+sheen: the sheen goes to KHR_materials_sheen, exact as a lobe (alone, it is the
// extension's BRDF); the body under it is not dimmed by the fit, so the export says so. Mitsuba
// 3 and pbrt-v4 have no Charlie sheen: they export the lambert+ggx part, exactly, and say that
// the sheen is left out.
TEST(ExportFormulas, SheenGoesToKhrMaterialsSheenAndIsLeftOutElsewhere) {
  ScratchDir dir;
  bool exact = true;
  const std::vector<double> body = {0.21, 0.13, 0.07, 0.05, 0.04, 0.03, 0.4};
  const std::vector<double> sheen = {0.6, 0.4, 0.5, 0.15};
  std::vector<double> all = body;
  all.insert(all.end(), sheen.begin(), sheen.end());
  const auto e = Entry("lambert+ggx+sheen", all);
  const fs::path gltf = Export(dir, e, Format::kGltf, "cloth.gltf", &exact);
  EXPECT_FALSE(exact);
  EXPECT_NE(ReadText(gltf).find("albedo scaling"), std::string::npos);
  const auto mat = GltfMaterial(gltf);
  const auto& ext = mat["extensions"]["KHR_materials_sheen"];
  EXPECT_NEAR(ext["sheenRoughnessFactor"].get<double>(), std::sqrt(0.15), 1e-15);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(ext["sheenColorFactor"][c].get<double>(), sheen[c]);
  std::ifstream in(gltf);
  const auto doc = nlohmann::json::parse(in);
  EXPECT_NE(std::find(doc["extensionsUsed"].begin(), doc["extensionsUsed"].end(),
                      "KHR_materials_sheen"),
            doc["extensionsUsed"].end());

  // The sheen alone: no body, no highlight.
  std::vector<double> only = {0, 0, 0, 0, 0, 0, 0.4};
  only.insert(only.end(), sheen.begin(), sheen.end());
  const auto lone = Entry("lambert+ggx+sheen", only);
  const auto lone_mat = GltfMaterial(Export(dir, lone, Format::kGltf, "lone.gltf", &exact));
  EXPECT_LT(MaxRelError(lone, [&](const Dirs& d) { return GltfSheenEval(lone_mat, d); }), 1e-12);

  // Mitsuba 3 and pbrt-v4: the lambert+ggx part, the sheen said to be left out.
  const auto part = Entry("lambert+ggx", body);
  const std::string xml = ReadText(Export(dir, e, Format::kMitsuba, "cloth.xml", &exact));
  EXPECT_FALSE(exact);
  EXPECT_NE(xml.find("sheen lobe"), std::string::npos);
  EXPECT_LT(MaxRelError(part, [&](const Dirs& d) { return MitsubaEval(xml, d); }), 1e-7);
  const std::string pbrt = ReadText(Export(dir, e, Format::kPbrt, "cloth.pbrt", &exact));
  EXPECT_FALSE(exact);
  EXPECT_NE(pbrt.find("sheen lobe"), std::string::npos);
}

// An entry of `model` with its parameters given by name (every one of the model's).
FitReportEntry EntryByName(const std::string& model, const std::map<std::string, double>& p) {
  const ModelInfo* m = FindModel(model);
  std::vector<double> params;
  for (const std::string& n : m->param_names) {
    EXPECT_EQ(p.count(n), 1u) << model << " " << n;
    params.push_back(p.count(n) ? p.at(n) : 0.0);
  }
  EXPECT_EQ(p.size(), params.size()) << model;
  return Entry(model, params);
}

// lambert+ggx+ggx, coloured lobes: exact in Mitsuba 3 (a nested blendbsdf of two
// roughconductors) and in Blender (a second Glossy BSDF added); pbrt-v4 nests two conductors
// (exact but for its height-correlated masking); glTF and the Principled BSDF keep the stronger
// lobe and say so.
TEST(ExportFormulas, TwoGgxLobesAreExactInMitsubaAndBlender) {
  ScratchDir dir;
  bool exact = false;
  // The second lobe is the stronger: the exports put it first.
  const auto e = EntryByName("lambert+ggx+ggx", {{"lambert.kd_r", 0.20},
                                                 {"lambert.kd_g", 0.12},
                                                 {"lambert.kd_b", 0.05},
                                                 {"ggx1.ks_r", 0.05},
                                                 {"ggx1.ks_g", 0.04},
                                                 {"ggx1.ks_b", 0.03},
                                                 {"ggx1.alpha", 0.30},
                                                 {"ggx2.ks_r", 0.50},
                                                 {"ggx2.ks_g", 0.40},
                                                 {"ggx2.ks_b", 0.35},
                                                 {"ggx2.alpha", 0.02}});
  const std::string xml = ReadText(Export(dir, e, Format::kMitsuba, "two.xml", &exact));
  EXPECT_TRUE(exact);
  EXPECT_EQ(MitsubaConductors(xml).size(), 2u);
  EXPECT_NEAR(MitsubaConductors(xml).at(0).first, 0.02, 1e-12);
  EXPECT_LT(MaxRelError(e, [&](const Dirs& d) { return MitsubaEval(xml, d); }), 1e-7);

  const std::string py = ReadText(Export(dir, e, Format::kBlender, "two.py", &exact));
  EXPECT_TRUE(exact);
  EXPECT_NEAR(PyNumber(py, "EXACT", "second_roughness"), std::sqrt(0.30), 1e-9);
  EXPECT_LT(MaxRelError(e, [&](const Dirs& d) { return BlenderExactEval(py, d); }), 1e-7);
  EXPECT_NE(py.find("the fit's weaker lobe"), std::string::npos) << "Principled: one lobe";

  // pbrt-v4: the same sum with height-correlated masking and its conductor Fresnel.
  const std::string pbrt = ReadText(Export(dir, e, Format::kPbrt, "two.pbrt", &exact));
  EXPECT_FALSE(exact);
  EXPECT_NE(pbrt.find("brdfit-specular-2"), std::string::npos);
  const auto hc = EntryByName("lambert+ggx+ggx", {{"lambert.kd_r", 0.20},
                                                  {"lambert.kd_g", 0.12},
                                                  {"lambert.kd_b", 0.05},
                                                  {"ggx1.ks_r", 0.05},
                                                  {"ggx1.ks_g", 0.05},
                                                  {"ggx1.ks_b", 0.05},
                                                  {"ggx1.alpha", 0.30},
                                                  {"ggx2.ks_r", 0.40},
                                                  {"ggx2.ks_g", 0.40},
                                                  {"ggx2.ks_b", 0.40},
                                                  {"ggx2.alpha", 0.02}});
  const std::string grey = ReadText(Export(dir, hc, Format::kPbrt, "grey.pbrt", &exact));
  const Dirs n = MakeDirs({0, 0, 1}, {0, 0, 1});
  const auto hc_sum = [&](const Dirs& d) {
    Rgb out{};
    for (int c = 0; c < 3; ++c) out[c] = hc.result.params[c] / kPi;
    for (const auto& [ks, a] : {std::pair{0.05, 0.30}, std::pair{0.40, 0.02}}) {
      const double lobe = GgxLobe(a, d, true);
      for (int c = 0; c < 3; ++c) out[c] += ks * lobe;
    }
    return out;
  };
  std::mt19937_64 rng(3);
  for (int k = 0; k < 500; ++k) {
    const Dirs d = k == 0 ? n : MakeDirs(RandomDir(rng), RandomDir(rng));
    const Rgb t = PbrtEval(grey, d), want = hc_sum(d);
    // pbrt's 0.9999 reflectance clamp: F dips by up to 4.3e-4 near grazing.
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(t[c], want[c], 1e-3 * want[c]) << k;
  }

  // glTF: the stronger lobe alone, and the note names the weaker one.
  const fs::path gltf = Export(dir, e, Format::kGltf, "two.gltf", &exact);
  EXPECT_FALSE(exact);
  EXPECT_NE(ReadText(gltf).find("the fit's weaker lobe (ks (0.05, 0.04, 0.03)"), std::string::npos);
  const auto mat = GltfMaterial(gltf);
  EXPECT_NEAR(mat["pbrMetallicRoughness"]["roughnessFactor"].get<double>(), std::sqrt(0.02), 1e-12);
}

// Rough bodies under a GGX lobe: Fujii's Oren-Nayar is Cycles' Diffuse BSDF with Roughness
// sigma and Burley 2012 a Principled BSDF with Specular 0, so both export to Blender exactly;
// Burley 2012 is also Mitsuba 3's principled with specular 0 (exact). Where the target's body
// is Lambert (glTF and pbrt-v4; Mitsuba 3 for Fujii) the body becomes the Lambert albedo equal
// to it at normal incidence and view, and the note says so.
TEST(ExportFormulas, RoughBodiesAreExactInBlenderAndLambertElsewhere) {
  ScratchDir dir;
  bool exact = false;
  const Dirs n = MakeDirs({0, 0, 1}, {0, 0, 1});
  const auto fujii = EntryByName("oren-nayar-fujii+ggx", {{"oren-nayar-fujii.kd_r", 0.45},
                                                          {"oren-nayar-fujii.kd_g", 0.25},
                                                          {"oren-nayar-fujii.kd_b", 0.12},
                                                          {"oren-nayar-fujii.sigma", 0.9},
                                                          {"ggx.ks_r", 0.08},
                                                          {"ggx.ks_g", 0.07},
                                                          {"ggx.ks_b", 0.06},
                                                          {"ggx.alpha", 0.2}});
  const auto burley = EntryByName("burley-2012+ggx", {{"burley-2012.kd_r", 0.35},
                                                      {"burley-2012.kd_g", 0.30},
                                                      {"burley-2012.kd_b", 0.40},
                                                      {"burley-2012.alpha", 0.7},
                                                      {"ggx.ks_r", 0.1},
                                                      {"ggx.ks_g", 0.1},
                                                      {"ggx.ks_b", 0.1},
                                                      {"ggx.alpha", 0.08}});
  for (const auto* e : {&fujii, &burley}) {
    SCOPED_TRACE(e->result.model);
    const std::string py = ReadText(Export(dir, *e, Format::kBlender, "b.py", &exact));
    EXPECT_TRUE(exact);
    EXPECT_LT(MaxRelError(*e, [&](const Dirs& d) { return BlenderExactEval(py, d); }), 1e-7);
    // The same script with the body's roughness set to 0 (a Lambert body) differs.
    const std::string key = "\"body_roughness\": ";
    const std::size_t at = py.find(key);
    ASSERT_NE(at, std::string::npos);
    const std::string flat = py.substr(0, at + key.size()) + "0" + py.substr(py.find(',', at));
    EXPECT_GT(MaxRelError(*e, [&](const Dirs& d) { return BlenderExactEval(flat, d); }), 1e-2);
    const std::string xml = ReadText(Export(dir, *e, Format::kMitsuba, "b.xml", &exact));
    if (e == &burley) {
      // Mitsuba 3's principled diffuse is Burley 2012's; the same file with a Lambert diffuse
      // in its place differs.
      EXPECT_TRUE(exact);
      EXPECT_EQ(xml.find("has a Lambert diffuse"), std::string::npos);
      EXPECT_LT(MaxRelError(*e, [&](const Dirs& d) { return MitsubaEval(xml, d); }), 1e-7);
      const std::string key = "<rgb name=\"base_color\"";
      const std::size_t at = xml.find(key), open = xml.find("<bsdf type=\"principled\"");
      ASSERT_NE(at, std::string::npos);
      ASSERT_NE(open, std::string::npos);
      std::string lambert = xml;
      lambert.replace(at, key.size(), "<rgb name=\"reflectance\"");
      lambert.replace(open, std::strlen("<bsdf type=\"principled\""), "<bsdf type=\"diffuse\"");
      EXPECT_GT(MaxRelError(*e, [&](const Dirs& d) { return MitsubaEval(lambert, d); }), 1e-2);
    } else {
      // The Lambert targets: approximate, said, and equal at normal incidence and view.
      EXPECT_FALSE(exact);
      EXPECT_NE(xml.find("has a Lambert diffuse"), std::string::npos);
      const Rgb t = MitsubaEval(xml, n), m = Model(*e, n);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], m[c], 1e-7 * m[c]) << c;
      EXPECT_GT(MaxRelError(*e, [&](const Dirs& d) { return MitsubaEval(xml, d); }), 1e-2);
    }
    const std::string pbrt = ReadText(Export(dir, *e, Format::kPbrt, "b.pbrt", &exact));
    EXPECT_FALSE(exact);
    EXPECT_NE(pbrt.find("has a Lambert diffuse"), std::string::npos);
    const fs::path gltf = Export(dir, *e, Format::kGltf, "b.gltf", &exact);
    EXPECT_FALSE(exact);
    EXPECT_NE(ReadText(gltf).find("has a Lambert diffuse"), std::string::npos);
  }
  // Burley's Principled material is the body's own shader with the lobe's roughness: it says so.
  const std::string py = ReadText(Export(dir, burley, Format::kBlender, "p.py", &exact));
  EXPECT_NE(py.find("one Roughness"), std::string::npos);
}

// A sheen lobe fitted to zero is no sheen: the export is the exact lambert+ggx, with no note.
TEST(ExportFormulas, ZeroSheenIsNoSheen) {
  ScratchDir dir;
  bool exact = false;
  const auto e =
      Entry("lambert+ggx+sheen", {0.21, 0.13, 0.07, 0.05, 0.04, 0.03, 0.4, 0, 0, 0, 0.3});
  const std::string xml = ReadText(Export(dir, e, Format::kMitsuba, "none.xml", &exact));
  EXPECT_TRUE(exact);
  EXPECT_EQ(xml.find("sheen lobe"), std::string::npos);
  EXPECT_LT(MaxRelError(e, [&](const Dirs& d) { return MitsubaEval(xml, d); }), 1e-7);
  const auto mat = GltfMaterial(Export(dir, e, Format::kGltf, "none.gltf", &exact));
  EXPECT_FALSE(mat.contains("extensions") && mat["extensions"].contains("KHR_materials_sheen"));
}

// Golden files: `brdfit export tests/export/data/fits.json` as of this commit (the fits of
// nbrdf:gold-metallic-paint and nbrdf:red-phenolic written by `brdfit fit ... --model
// ggx-hc,ggx,ggx-f0,ue4 --json`), checked by hand against docs/exports.md's tables and by the
// formula tests above. A change of the exporters must be a deliberate change of these files
// (regenerate with tests/export/README.md's commands).
TEST(ExportGolden, FilesMatch) {
  const fs::path src = BRDFIT_SOURCE_DIR;
  const auto entries = ReadFitParamsJson(src / "tests/export/data/fits.json");
  ScratchDir dir;
  struct Case {
    const char* material;
    const char* model;
    Format format;
    const char* golden;
  };
  for (const Case& c :
       {Case{"gold-metallic-paint", "", Format::kMitsuba, "gold-metallic-paint.xml"},
        Case{"gold-metallic-paint", "", Format::kPbrt, "gold-metallic-paint.pbrt"},
        Case{"red-phenolic", "lambert+ggx-hc", Format::kGltf, "red-phenolic.gltf"},
        Case{"red-phenolic", "ue4", Format::kPbrt, "red-phenolic-ue4.pbrt"}}) {
    const auto& e = exports::SelectEntry(entries, c.material, c.model, c.format);
    const fs::path out = dir.path() / c.golden;
    exports::WriteExport(e, "fits.json", c.format, out);
    EXPECT_EQ(ReadText(out), ReadText(src / "tests/export/golden" / c.golden)) << c.golden;
  }
}

// The default: the chosen fit when the format expresses it exactly, else the best-scored fit it
// does (a note names the chosen one and the gap), else the best exportable one.
TEST(ExportSelect, ChoosesTheExactModelAndRefusesTheUnexportable) {
  const fs::path src = BRDFIT_SOURCE_DIR;
  const auto entries = ReadFitParamsJson(src / "tests/export/data/fits.json");
  EXPECT_THROW(exports::SelectEntry(entries, "", "", Format::kGltf), InputError);  // 2 materials
  // gold-metallic-paint: brdfit chose lambert+ggx, exact in Mitsuba and Blender. pbrt-v4
  // expresses neither lambert+ggx (coloured, other masking) nor lambert+ggx-hc (coloured)
  // exactly, and keeps every lobe of both: the chosen one.
  for (const Format f : {Format::kMitsuba, Format::kBlender, Format::kPbrt}) {
    const auto& e = exports::SelectEntry(entries, "gold-metallic-paint", "", f);
    EXPECT_EQ(e.result.model, "lambert+ggx");
    EXPECT_EQ(exports::SelectionNote(entries, e, f), "");
  }
  // A chosen fit whose export leaves a lobe out (lambert+ggx+ggx in glTF: one lobe) gives way
  // to a fit that keeps its every lobe, and the note gives the gap.
  std::vector<FitReportEntry> two = entries;
  for (auto& e : two) e.chosen = false;
  auto lobes = EntryByName("lambert+ggx+ggx", {{"lambert.kd_r", 0.2},
                                               {"lambert.kd_g", 0.1},
                                               {"lambert.kd_b", 0.05},
                                               {"ggx1.ks_r", 0.05},
                                               {"ggx1.ks_g", 0.05},
                                               {"ggx1.ks_b", 0.05},
                                               {"ggx1.alpha", 0.3},
                                               {"ggx2.ks_r", 0.4},
                                               {"ggx2.ks_g", 0.4},
                                               {"ggx2.ks_b", 0.4},
                                               {"ggx2.alpha", 0.02}});
  lobes.material = "gold-metallic-paint";
  lobes.chosen = true;
  two.push_back(lobes);
  const auto& gltf = exports::SelectEntry(two, "gold-metallic-paint", "", Format::kGltf);
  EXPECT_NE(gltf.result.model, "lambert+ggx+ggx");
  const std::string note = exports::SelectionNote(two, gltf, Format::kGltf);
  EXPECT_NE(note.find("brdfit chose lambert+ggx+ggx for this material, which gltf expresses only "
                      "approximately: exporting " +
                      gltf.result.model),
            std::string::npos)
      << note;
  // red-phenolic: brdfit chose lambert+ggx-f0 (Schlick Fresnel), which Mitsuba's
  // roughconductor (no Fresnel) does not express: the best-scored exact fit instead.
  const auto& mitsuba = exports::SelectEntry(entries, "red-phenolic", "", Format::kMitsuba);
  EXPECT_EQ(mitsuba.result.model, "lambert+ggx");
  EXPECT_NE(exports::SelectionNote(entries, mitsuba, Format::kMitsuba).find("lambert+ggx-f0"),
            std::string::npos);
  // glTF expresses neither exactly, each in one way (a coloured ks; the diffuse weighted by
  // 1 - max F): the chosen one.
  EXPECT_EQ(exports::SelectEntry(entries, "red-phenolic", "", Format::kGltf).result.model,
            "lambert+ggx-f0");
  // three.js evaluates every model: the chosen fit.
  EXPECT_EQ(exports::SelectEntry(entries, "red-phenolic", "", Format::kThreejs).result.model,
            "lambert+ggx-f0");
  // --model wins, and must be exportable.
  EXPECT_EQ(exports::SelectEntry(entries, "red-phenolic", "ue4", Format::kGltf).result.model,
            "ue4");
  EXPECT_THROW(exports::SelectEntry(entries, "red-phenolic", "ward", Format::kGltf), InputError);
  EXPECT_THROW(exports::SelectEntry(entries, "no-such", "", Format::kGltf), InputError);
  auto e = Entry("lambert+abc", std::vector<double>(FindModel("lambert+abc")->params.size(), 0.1));
  EXPECT_THROW(exports::WriteExport(e, "x", Format::kGltf, "/nonexistent/x.gltf"), InputError);
}

}  // namespace
}  // namespace brdfit
