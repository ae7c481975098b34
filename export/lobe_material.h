// A fit as "Lambert + one GGX lobe", the form every export target is built from
// (docs/exports.md): which fitted models can be exported and what their parameters mean.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/result.h"

namespace brdfit::exports {

using Rgb = std::array<double, 3>;

// How the source's GGX lobe masks: brdfit's ggx (separable Smith, Walter 2007 eq. 34 squared),
// ggx-hc / ggx-f0 (height-correlated, Heitz 2014 eq. 99), ue4 (Schlick-Smith, Karis 2013 eq. 4).
enum class Masking { kSeparable, kHeightCorrelated, kSchlickSmithUe4 };

// The source's Fresnel: none (ks has it folded in: a constant weight, NOT F0), or Schlick's
// with a per-channel F0.
enum class LobeFresnel { kFoldedIntoKs, kSchlick };

//   f_r = kd / pi + spec D_GGX(alpha) G / (4 cos_i cos_o)                 (kFoldedIntoKs)
//   f_r = kd / pi + F_Schlick(spec, cos_d) D_GGX(alpha) G / (4 cos_i cos_o) (kSchlick)
// plus, for lambert+ggx+sheen, the Charlie sheen lobe of models/sheen.h (sheen = true),
// and, for ue4, its own metallic-roughness parameters (diffuse (1 - m) base / pi, F0 =
// mix(0.04, base, m)), which kd and spec restate without the Schlick-Smith G.
// The body under the lobes: Lambert kd / pi; Fujii's Oren-Nayar kd A (1 + sigma s / t)
// (models/oren_nayar.h, Cycles' Diffuse BSDF); Burley 2012's diffuse (models/burley.h, Cycles'
// Principled diffuse).
enum class Body { kLambert, kOrenNayarFujii, kBurley2012 };

struct LobeMaterial {
  std::string model;  // registry name of the source fit
  Rgb kd{};           // the body's albedo (Lambert: f_d = kd / pi)
  Body body = Body::kLambert;
  double body_roughness = 0;  // oren-nayar-fujii: sigma; burley-2012: r = sqrt(alpha)
  Rgb spec{};         // ks (kFoldedIntoKs) or F0 (kSchlick)
  double alpha = 0;   // GGX alpha (glTF / Blender roughness = sqrt(alpha))
  Masking masking = Masking::kSeparable;
  LobeFresnel fresnel = LobeFresnel::kFoldedIntoKs;
  bool ue4 = false;  // then base and metallic hold its own parameters
  Rgb base{};
  double metallic = 0;
  // lambert+ggx+ggx: a second GGX lobe of the same form (separable masking, ks a constant
  // weight), added: + ks2 D_GGX(alpha2) G / (4 cos_i cos_o) (models/sum.h). FromFit puts the
  // lobe with the larger max ks first, so that a target with one lobe keeps the stronger.
  struct SecondLobe {
    Rgb spec{};
    double alpha = 0;
  };
  std::optional<SecondLobe> second;
  // lambert+ggx+sheen: + sheen D_Charlie(sheen_alpha) V_Neubelt, added (models/sheen.h). A
  // fitted sheen colour of 0 in every channel is no sheen: `sheen` stays false.
  bool sheen = false;
  Rgb sheen_color{};
  double sheen_alpha = 0;  // glTF sheenRoughness = sqrt(sheen_alpha)
};

// The models export reads, comma-separated, for messages.
const char* ExportableModels();
bool IsExportable(const std::string& model);

// Throws InputError for a failed fit or a model outside ExportableModels().
LobeMaterial FromFit(const FitResult& fit);

}  // namespace brdfit::exports
