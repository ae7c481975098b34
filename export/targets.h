// A LobeMaterial in each target renderer's own parameters, with what the target cannot express
// (docs/exports.md has the formulas and the tables; tests/export checks them against the
// targets' documented BSDFs).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "export/lobe_material.h"

namespace brdfit::exports {

// What did not carry over exactly; empty = exact (up to the noted tolerance of the target).
struct Fidelity {
  std::vector<std::string> approximations;
  // How many of the fit's lobes the target leaves out (a second GGX lobe, a sheen): each is in
  // `approximations` too. A dropped lobe loses far more than the other approximations (a
  // masking form, a coloured ks, a layering), so the selection of exports weighs it first.
  int dropped_lobes = 0;
  bool Exact() const { return approximations.empty(); }
};

// glTF 2.0 metallic-roughness (Appendix B) with KHR_materials_specular and KHR_materials_ior:
// dielectric = (1 - w max(Fr)) baseColor / pi + w Fr D V, Fr = f0 + (1 - f0)(1 - v.h)^5,
// f0 = min(((ior - 1)/(ior + 1))^2 specularColor, 1), w = specularFactor; V height-correlated.
// The default ior 1.5 is kept (0.04 specularColor = F0), so ior_ext stays false. A sheen lobe
// goes to KHR_materials_sheen (sheenColorFactor, sheenRoughnessFactor = sqrt(alpha)).
struct GltfPbr {
  Rgb base_color{};
  double metallic = 0;
  double roughness = 0;  // sqrt(alpha)
  bool specular_ext = false;
  double specular_factor = 1;
  Rgb specular_color{1, 1, 1};
  bool ior_ext = false;
  double ior = 1.5;
  // KHR_materials_sheen: f = sheenColor D_Charlie V + base layer x sheen albedo scaling.
  bool sheen_ext = false;
  Rgb sheen_color{};
  double sheen_roughness = 0;  // sqrt(sheen alpha)
  Fidelity fidelity;
};
GltfPbr ToGltf(const LobeMaterial& m);

// Mitsuba 3: blendbsdf(weight) of diffuse(reflectance) and roughconductor(ggx, alpha,
// material="none", specular_reflectance): (1 - w) R / pi + w S D G1 G1 / (4 cos_i cos_o).
// A second lobe: the roughconductor becomes blendbsdf(second->weight = v) of the two
// roughconductors, (1 - w) R / pi + w ((1 - v) S lobe + v S2 lobe2).
// A Burley 2012 body is Mitsuba's principled BSDF in place of the diffuse, base_color R,
// roughness r, specular 0 (eta 1: its dielectric Fresnel, hence its specular lobe, is 0),
// metallic 0: its diffuse alone, R / pi ((1 - FL/2)(1 - FO/2) + RR (FL + FO + FL FO (RR - 1))),
// RR = 2 r cos_d^2 (Mitsuba 3 src/bsdfs/principled.cpp, eval), which is Burley 2012's
// (1 + (F_D90 - 1) FL)(1 + (F_D90 - 1) FO) with F_D90 = 0.5 + RR (models/burley.h): exact.
// Fujii's Oren-Nayar has no Mitsuba 3 plugin: it becomes a Lambert diffuse (approximate).
struct MitsubaBlend {
  double weight = 0;
  Body body = Body::kLambert;  // kLambert (diffuse) or kBurley2012 (principled)
  double body_roughness = 0;   // the principled body's roughness r = sqrt(alpha)
  Rgb diffuse_reflectance{};   // diffuse reflectance, or the principled body's base_color
  Rgb specular_reflectance{};
  double alpha = 0;
  struct Second {
    double weight = 0;  // v, the inner blend's weight
    Rgb specular_reflectance{};
    double alpha = 0;
  };
  std::optional<Second> second;
  Fidelity fidelity;
};
MitsubaBlend ToMitsuba(const LobeMaterial& m);

// pbrt-v4: mix(amount) of diffuse(reflectance) and conductor(reflectance, roughness = alpha,
// remaproughness false): (1 - a) R / pi + a F_conductor D G / (4 cos_i cos_o), G
// height-correlated; reflectance r gives eta = 1, k = 2 sqrt(r) / sqrt(1 - r), r <= 0.9999.
// A second lobe: the conductor becomes mix(second->amount = v) of the two conductors,
// (1 - a) R / pi + a ((1 - v) F_r lobe + v F_r2 lobe2); pbrt-v4 resolves nested mixes.
struct PbrtMix {
  double amount = 0;
  Rgb diffuse_reflectance{};
  Rgb conductor_reflectance{};
  double roughness = 0;
  struct Second {
    double amount = 0;  // v, the inner mix's amount
    Rgb conductor_reflectance{};
    double roughness = 0;
  };
  std::optional<Second> second;
  Fidelity fidelity;
};
PbrtMix ToPbrt(const LobeMaterial& m);

// Blender 3.4 Cycles. The sphere's material is an Add Shader of a Diffuse BSDF (roughness 0:
// Lambert, colour kd) and a Glossy BSDF (GGX, colour ks, roughness sqrt(alpha)):
// kd / pi + ks D G1 G1 / (4 cos_i cos_o), no Fresnel, separable Smith masking (Cycles 3.4's
// microfacet closure) -- brdfit's lambert+ggx exactly. The script also builds a Principled BSDF
// (3.4, distribution GGX) for glTF round trips and Blender users:
// (1 - m) base / pi * Burley(r) + F D G1 G1 / (4 cos_i cos_o), F rising from
// cspec0 = (1 - m) 0.08 specular ((1 - tint) + tint base / lum(base)) + m base to 1 at grazing;
// metallic m is 0 (base kd) or, when that is nearer, 1 (base ks, no diffuse). It is never exact
// for a brdfit model (docs/exports.md, "Blender").
// A second lobe adds a second Glossy BSDF (second->glossy_color, roughness sqrt(alpha2)) to the
// sum: lambert+ggx+ggx exactly.
// A rough body keeps its own shader, exact in Cycles: Fujii's Oren-Nayar is the Diffuse BSDF
// with Roughness sigma (bsdf_oren_nayar.h); Burley 2012 is a Principled BSDF with Specular 0,
// Metallic 0 and Roughness r (its diffuse alone, bsdf_principled_diffuse.h), whose Base Color
// is kd: oren-nayar-fujii+ggx and burley-2012+ggx exactly.
struct BlenderMaterial {
  Body body = Body::kLambert;
  double body_roughness = 0;  // the Diffuse BSDF's sigma or the Principled body's r
  Rgb diffuse_color{};
  Rgb glossy_color{};
  double roughness = 0;  // sqrt(alpha), both shaders
  struct Second {
    Rgb glossy_color{};
    double roughness = 0;  // sqrt(alpha2)
  };
  std::optional<Second> second;
  Fidelity fidelity;     // of the Diffuse + Glossy node tree
  Rgb base_color{};      // Principled: kd (metallic 0) or ks (metallic 1)
  double metallic = 0;
  double specular = 0.5;
  double specular_tint = 0;
  Rgb principled_f0{};  // the cspec0 these give (Cycles' normal-incidence colour)
  Fidelity principled_fidelity;
};
BlenderMaterial ToBlender(const LobeMaterial& m);

}  // namespace brdfit::exports
