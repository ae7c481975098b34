#include "export/targets.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/oren_nayar.h"

namespace brdfit::exports {

namespace {

// 1 / ((1.5 - 1) / (1.5 + 1))^2: the specularColorFactor of F0 = 1 at glTF's default ior 1.5.
constexpr double kSpecularColorPerF0 = 25.0;

double Max(const Rgb& v) {
  return std::max({v[0], v[1], v[2]});
}
bool Grey(const Rgb& v) {
  return Max(v) - std::min({v[0], v[1], v[2]}) <= 1e-9 * Max(v);
}

// A Fresnel that is f0 = ks / max ks at normal incidence and 1 at grazing: the weakest
// channel's factor at grazing, max ks / min ks.
double GrazingFactor(const Rgb& ks) {
  const double lo = std::min({ks[0], ks[1], ks[2]});
  return lo > 0 ? Max(ks) / lo : std::numeric_limits<double>::infinity();
}

std::string Fmt3(const Rgb& v) {
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", v[0], v[1], v[2]);
}

// kd / (1 - w), clipped to 1 (an albedo), noting the clip.
Rgb DiffuseOver(const Rgb& kd, double w, const char* what, Fidelity* f) {
  Rgb out{};
  bool clipped = false;
  for (int c = 0; c < 3; ++c) {
    const double v = w < 1 ? kd[c] / (1 - w) : (kd[c] > 0 ? 2.0 : 0.0);
    out[c] = std::min(v, 1.0);
    clipped = clipped || v > 1;
  }
  if (clipped) {
    f->approximations.push_back(fmt::format(
        "{} kd / (1 - {:.4g}) exceeds 1 for kd = {}: clipped to 1 (the diffuse part is darker)",
        what, w, Fmt3(kd)));
  }
  return out;
}

void NoteMasking(const LobeMaterial& m, Masking target, const char* target_name, Fidelity* f) {
  if (m.masking == target) return;
  const char* src = m.masking == Masking::kSeparable          ? "separable Smith G (brdfit ggx)"
                    : m.masking == Masking::kHeightCorrelated ? "height-correlated Smith G"
                                                              : "Schlick-Smith G (ue4)";
  const char* dst = target == Masking::kSeparable ? "separable" : "height-correlated";
  f->approximations.push_back(fmt::format(
      "{} masks with {} Smith G, the fit with {}: same alpha exported, the lobe differs towards "
      "grazing (fit lambert+{} for an exact export)",
      target_name, dst, src, target == Masking::kSeparable ? "ggx" : "ggx-hc"));
}

// The constant-weight lobe an F0 lobe is nearest to at normal incidence, for targets without
// a Schlick Fresnel on a free weight.
Rgb ConstantWeight(const LobeMaterial& m, const char* target_name, Fidelity* f) {
  if (m.fresnel == LobeFresnel::kFoldedIntoKs) return m.spec;
  f->approximations.push_back(fmt::format(
      "{}: the fit's Schlick Fresnel (F0 = {}) is exported as a constant weight F0 (no rise "
      "towards grazing)",
      target_name, Fmt3(m.spec)));
  if (m.ue4) {
    f->approximations.push_back(
        "ue4's base colour and metallic are exported as Lambert kd = (1 - m) base and F0 = "
        "mix(0.04, base, m)");
  }
  return m.spec;
}

// A target without the Charlie sheen: the lobe is left out, and said.
void NoteSheenDropped(const LobeMaterial& m, const char* target_name, Fidelity* f) {
  if (!m.sheen) return;
  ++f->dropped_lobes;
  f->approximations.push_back(fmt::format(
      "{} has no Charlie sheen: the fit's sheen lobe (colour {}, alpha {:.4g}) is left out, so "
      "the material is darker towards grazing (three.js and glTF carry it)",
      target_name, Fmt3(m.sheen_color), m.sheen_alpha));
}

// A target with one GGX lobe: the fit's second lobe is left out, and said.
void NoteSecondLobeDropped(const LobeMaterial& m, const char* target_name, const char* why,
                           Fidelity* f) {
  if (!m.second) return;
  ++f->dropped_lobes;
  f->approximations.push_back(fmt::format(
      "{} has one GGX lobe{}: the fit's weaker lobe (ks {}, alpha {:.4g}) is left out, so the "
      "material is darker (Blender's node tree, Mitsuba 3, pbrt-v4 and three.js carry it)",
      target_name, why, Fmt3(m.second->spec), m.second->alpha));
}

// A target whose diffuse is Lambert: a rough body becomes the Lambert albedo equal to it at
// normal incidence and view (Fujii's Oren-Nayar: kd pi A, models/oren_nayar.h; Burley 2012:
// kd), and the note says what is lost.
Rgb LambertBody(const LobeMaterial& m, const char* target_name, Fidelity* f) {
  if (m.body == Body::kLambert) return m.kd;
  if (m.body == Body::kBurley2012) {
    f->approximations.push_back(fmt::format(
        "{} has a Lambert diffuse: the fit's Burley 2012 body (r = {:.4g}) is exported as Lambert "
        "kd = {}, equal at normal incidence and view; its grazing retro-reflection and darkening "
        "are lost (Blender's Principled BSDF and Mitsuba 3's principled carry it)",
        target_name, m.body_roughness, Fmt3(m.kd)));
    return m.kd;
  }
  const double sigma = m.body_roughness;
  const double scale = kPi * OrenNayarFujii::A(sigma);
  Rgb kd{};
  for (int c = 0; c < 3; ++c) kd[c] = m.kd[c] * scale;
  f->approximations.push_back(fmt::format(
      "{} has a Lambert diffuse: the fit's Oren-Nayar body (Fujii, sigma = {:.4g}) is exported as "
      "Lambert kd = {} ({:.4g} kd, equal at normal incidence and view); its flattening towards "
      "grazing is lost (Blender's Diffuse BSDF carries it)",
      target_name, sigma, Fmt3(kd), scale));
  return kd;
}

// KHR_materials_sheen: the sheen lobe over the base layer, which the extension dims by its
// albedo scaling min(1 - max(sheenColor) E(cos_o), 1 - max(sheenColor) E(cos_i)) (E the sheen's
// directional albedo); the fit adds the lobe to an undimmed body.
void SheenToGltf(const LobeMaterial& m, GltfPbr* g) {
  if (!m.sheen) return;
  g->sheen_ext = true;
  g->sheen_color = m.sheen_color;
  g->sheen_roughness = std::sqrt(std::max(m.sheen_alpha, 0.0));
  g->fidelity.approximations.push_back(fmt::format(
      "KHR_materials_sheen dims the layer below the sheen by its albedo scaling, the fit adds "
      "the sheen to an undimmed body: the body is darker by max(sheenColor) E = {:.4g} E "
      "(E <= 1, the sheen's directional albedo, largest at grazing); viewers evaluate the sheen "
      "with Neubelt's visibility (three.js, the fit's) or Charlie's (Khronos Sample Viewer)",
      Max(m.sheen_color)));
}

}  // namespace

GltfPbr ToGltf(const LobeMaterial& m) {
  GltfPbr g;
  g.roughness = std::sqrt(std::max(m.alpha, 0.0));
  Fidelity& f = g.fidelity;
  SheenToGltf(m, &g);
  NoteSecondLobeDropped(m, "glTF 2.0",
                        " (KHR_materials_clearcoat's coat has the Fresnel of ior 1.5 and dims the "
                        "layer below: not an added lobe)",
                        &f);
  if (m.ue4) {
    // Karis 2013 is glTF's own parameterization: base colour, metallic, roughness = sqrt(alpha).
    g.base_color = m.base;
    g.metallic = m.metallic;
    NoteMasking(m, Masking::kHeightCorrelated, "glTF", &f);
    f.approximations.push_back(
        "glTF weights the dielectric diffuse by (1 - F) (Appendix B fresnel_mix), ue4 does not");
    return g;
  }
  NoteMasking(m, Masking::kHeightCorrelated, "glTF", &f);
  const Rgb kd = LambertBody(m, "glTF 2.0", &f);
  // The default ior 1.5 gives ((ior - 1)/(ior + 1))^2 = 0.04, so specularColor = 25 F0 puts F0
  // itself under KHR_materials_specular's min(0.04 specularColor, 1) (specularColorFactor has
  // no upper bound). KHR_materials_ior's ior = 0 would do the same, but three.js documents ior
  // in [1, 2.333]: the default ior is what every viewer reads alike.
  g.specular_ext = true;
  if (m.fresnel == LobeFresnel::kSchlick) {
    // Fr = F0 + (1 - F0)(1 - v.h)^5 with w = 1 is the fit's lobe; the diffuse is weighted by
    // 1 - max(Fr) in glTF and by 1 in the fit: matched at normal incidence.
    g.specular_factor = 1;
    for (int c = 0; c < 3; ++c) g.specular_color[c] = kSpecularColorPerF0 * m.spec[c];
    const double f0 = std::min(Max(m.spec), 0.999);
    g.base_color = DiffuseOver(kd, f0, "glTF base colour", &f);
    f.approximations.push_back(fmt::format(
        "glTF weights the diffuse by 1 - max(Fr) (the fit by 1): base colour = kd / (1 - {:.4g}), "
        "exact at normal incidence, darker towards grazing",
        f0));
    return g;
  }
  // ks has Fresnel folded in: a constant weight, not F0. Fr = 1 for the largest channel
  // (specularColor = ks / max ks), so w max(Fr) = w = max ks and the diffuse weight 1 - w is
  // constant: exact for a grey ks; a coloured ks is exact at normal incidence and whitens
  // towards grazing in its other channels.
  double w = Max(m.spec);
  if (w > 1) {
    f.approximations.push_back(
        fmt::format("max ks = {:.4g} > 1: glTF's specular factor is clipped to 1", w));
    w = 1;
  }
  g.specular_factor = w;
  for (int c = 0; c < 3; ++c) {
    g.specular_color[c] = kSpecularColorPerF0 * (w > 0 ? std::min(m.spec[c] / w, 1.0) : 1.0);
  }
  if (!Grey(m.spec)) {
    f.approximations.push_back(fmt::format(
        "coloured ks = {}: glTF's Fresnel rises to white at grazing, so the channels below the "
        "largest are exact at normal incidence only (up to {:.4g} times too bright at grazing)",
        Fmt3(m.spec), GrazingFactor(m.spec)));
  }
  g.base_color = DiffuseOver(kd, w, "glTF base colour", &f);
  return g;
}

MitsubaBlend ToMitsuba(const LobeMaterial& m) {
  MitsubaBlend b;
  Fidelity& f = b.fidelity;
  NoteSheenDropped(m, "Mitsuba 3", &f);
  b.alpha = m.alpha;
  NoteMasking(m, Masking::kSeparable, "Mitsuba 3 roughconductor", &f);
  const Rgb ks = ConstantWeight(m, "Mitsuba 3", &f);
  // Burley 2012's body is Mitsuba's principled diffuse (targets.h); others become Lambert.
  const bool principled_body = m.body == Body::kBurley2012;
  const Rgb kd = principled_body ? m.kd : LambertBody(m, "Mitsuba 3's diffuse", &f);
  if (principled_body) {
    b.body = Body::kBurley2012;
    b.body_roughness = m.body_roughness;
  }
  // (1 - w) R / pi + w S lobe with R = kd / (1 - w), S = ks / w; w splits the two so that both
  // reflectances stay in [0, 1] when kd + ks <= 1. A second lobe shares w with the first by the
  // inner weight v = max ks2 / (max ks + max ks2): S = ks / (w (1 - v)), S2 = ks2 / (w v), every
  // reflectance's largest channel max kd + max ks + max ks2.
  const double kd_max = Max(kd), ks_max = Max(ks);
  const double ks2_max = m.second ? Max(m.second->spec) : 0, lobes = ks_max + ks2_max;
  b.weight = lobes + kd_max > 0 ? lobes / (lobes + kd_max) : 0.5;
  const double v = m.second ? (lobes > 0 ? ks2_max / lobes : 0.5) : 0;
  const double w1 = b.weight * (1 - v), w2 = b.weight * v;
  for (int c = 0; c < 3; ++c) b.specular_reflectance[c] = w1 > 0 ? ks[c] / w1 : 0;
  if (m.second) {
    MitsubaBlend::Second s2;
    s2.weight = v;
    s2.alpha = m.second->alpha;
    for (int c = 0; c < 3; ++c) s2.specular_reflectance[c] = w2 > 0 ? m.second->spec[c] / w2 : 0;
    b.second = s2;
  }
  b.diffuse_reflectance = DiffuseOver(kd, b.weight, "Mitsuba diffuse reflectance", &f);
  if (std::max(Max(b.specular_reflectance), b.second ? Max(b.second->specular_reflectance) : 0) >
      1) {
    f.approximations.push_back(
        "kd + ks exceeds 1: the specular_reflectance is above 1 (exact in Mitsuba's RGB "
        "variants, clipped by its spectral ones)");
  }
  return b;
}

PbrtMix ToPbrt(const LobeMaterial& m) {
  PbrtMix p;
  Fidelity& f = p.fidelity;
  NoteSheenDropped(m, "pbrt-v4", &f);
  p.roughness = m.alpha;
  NoteMasking(m, Masking::kHeightCorrelated, "pbrt-v4 conductor", &f);
  const Rgb ks = ConstantWeight(m, "pbrt-v4", &f);
  const Rgb kd = LambertBody(m, "pbrt-v4's diffuse", &f);
  // The conductor's Fresnel is at most 1: its reflectance is ks / max ks (pbrt clamps to
  // 0.9999, so F >= 0.9999 for a grey ks) and the mix amount carries max ks. A second lobe:
  // amount max ks + max ks2, shared by the inner mix's v = max ks2 / (max ks + max ks2).
  const double ks_max = Max(ks), ks2_max = m.second ? Max(m.second->spec) : 0;
  double a = ks_max + ks2_max;
  if (a > 1) {
    f.approximations.push_back(fmt::format("{} = {:.4g} > 1: pbrt-v4's mix amount is clipped to 1",
                                           m.second ? "max ks + max ks2" : "max ks", a));
    a = 1;
  }
  p.amount = a;
  const double v = m.second ? (a > 0 ? ks2_max / (ks_max + ks2_max) : 0.5) : 0;
  const auto reflectance = [&](const Rgb& k, double weight) {
    Rgb r{};
    for (int c = 0; c < 3; ++c) r[c] = weight > 0 ? std::min(k[c] / weight, 1.0) : 1.0;
    if (!Grey(k)) {
      f.approximations.push_back(fmt::format(
          "coloured ks = {}: pbrt-v4's conductor Fresnel (eta = 1, k from reflectance) rises to "
          "white at grazing, so the channels below the largest are exact at normal incidence "
          "only (up to {:.4g} times too bright at grazing)",
          Fmt3(k), GrazingFactor(k)));
    }
    return r;
  };
  p.conductor_reflectance = reflectance(ks, a * (1 - v));
  if (m.second) {
    PbrtMix::Second s2;
    s2.amount = v;
    s2.roughness = m.second->alpha;
    s2.conductor_reflectance = reflectance(m.second->spec, a * v);
    p.second = s2;
  }
  p.diffuse_reflectance = DiffuseOver(kd, a, "pbrt-v4 diffuse reflectance", &f);
  return p;
}

namespace {

// Cycles 3.4 Principled BSDF (svm_closure.h): the luminance its Specular Tint divides by.
double CyclesTintLuminance(const Rgb& c) {
  return 0.3 * c[0] + 0.6 * c[1] + 0.1 * c[2];
}

// The nearest A + B kd to ks with A, B >= 0 (least squares over the channels): the colours a
// metallic-0 Principled BSDF's cspec0 = 0.08 specular ((1 - t) + t kd / lum(kd)) can take.
std::array<double, 2> GreyPlusTint(const Rgb& ks, const Rgb& kd) {
  const double mk = (kd[0] + kd[1] + kd[2]) / 3, ms = (ks[0] + ks[1] + ks[2]) / 3;
  double sxx = 0, sxy = 0;
  for (int c = 0; c < 3; ++c) {
    sxx += (kd[c] - mk) * (kd[c] - mk);
    sxy += (kd[c] - mk) * (ks[c] - ms);
  }
  double b = sxx > 1e-18 ? sxy / sxx : 0, a = ms - b * mk;
  if (b < 0 || CyclesTintLuminance(kd) <= 0) {
    b = 0;
    a = ms;
  } else if (a < 0) {
    double kk = 0, ksk = 0;
    for (int c = 0; c < 3; ++c) {
      kk += kd[c] * kd[c];
      ksk += kd[c] * ks[c];
    }
    a = 0;
    b = kk > 0 ? std::max(ksk / kk, 0.0) : 0;
  }
  return {std::max(a, 0.0), b};
}

}  // namespace

BlenderMaterial ToBlender(const LobeMaterial& m) {
  BlenderMaterial b;
  b.roughness = std::sqrt(std::max(m.alpha, 0.0));
  // The exact node tree: Diffuse BSDF + Glossy BSDF (GGX, no Fresnel, separable masking).
  Fidelity& f = b.fidelity;
  NoteSheenDropped(m, "Blender's Diffuse + Glossy node tree", &f);
  NoteMasking(m, Masking::kSeparable, "Cycles 3.4 Glossy BSDF (GGX)", &f);
  const Rgb ks = ConstantWeight(m, "Blender", &f);
  // The body: Diffuse BSDF (roughness 0: Lambert; sigma: Fujii's Oren-Nayar) or, for Burley
  // 2012, a Principled BSDF reduced to its diffuse (Specular 0, Metallic 0, roughness r).
  b.body = m.body;
  b.body_roughness = m.body_roughness;
  b.diffuse_color = m.kd;
  b.glossy_color = ks;
  if (m.second) {
    b.second = BlenderMaterial::Second{m.second->spec, std::sqrt(std::max(m.second->alpha, 0.0))};
  }

  // The Principled BSDF, metallic 0: base colour kd, cspec0 = A + B kd nearest to ks.
  Fidelity& p = b.principled_fidelity;
  NoteSheenDropped(m, "Cycles 3.4's Principled BSDF (its Sheen is Burley's, not Charlie's)", &p);
  NoteSecondLobeDropped(m, "Cycles 3.4's Principled BSDF", " (its Clearcoat has a fixed Fresnel)",
                        &p);
  b.base_color = m.kd;
  const auto [a, slope] = GreyPlusTint(ks, m.kd);
  const double lum = CyclesTintLuminance(m.kd);
  const double grey_f0 = a + slope * lum;  // 0.08 specular
  b.specular = grey_f0 / 0.08;
  b.specular_tint = grey_f0 > 0 ? slope * lum / grey_f0 : 0;
  double worst = 0, off = 0, kd_sum = 0;
  for (int c = 0; c < 3; ++c) {
    b.principled_f0[c] = a + slope * m.kd[c];
    const double scale = std::max(std::abs(ks[c]), 1e-12);
    worst = std::max(worst, std::abs(b.principled_f0[c] - ks[c]) / scale);
    off += std::abs(b.principled_f0[c] - ks[c]);
    kd_sum += m.kd[c];
  }
  if (kd_sum < off) {
    // A coloured lobe over (nearly) no diffuse: metallic 1 makes cspec0 = base = ks exactly and
    // drops the diffuse, which loses less (sum kd) than the metallic-0 colour error (sum |off|).
    b.metallic = 1;
    b.base_color = ks;
    b.specular = 0.5;
    b.specular_tint = 0;
    b.principled_f0 = ks;
    worst = 0;
    if (kd_sum > 0) {
      p.approximations.push_back(fmt::format(
          "Principled: metallic 1 (base colour = ks) carries the coloured lobe; the diffuse "
          "kd = {} is dropped",
          Fmt3(m.kd)));
    }
  } else if (grey_f0 >= 0.999) {
    b.specular = 0.999 / 0.08;
    p.approximations.push_back(fmt::format(
        "Principled: 0.08 specular = {:.4g} >= 1 has no IOR: specular clipped to {:.4g}", grey_f0,
        b.specular));
  }
  p.approximations.push_back(
      "Principled: Cycles' Fresnel rises from cspec0 at normal incidence to 1 at grazing (the "
      "dielectric Fresnel of the IOR that Specular gives); the fit's ks is a constant weight");
  if (m.body == Body::kBurley2012) {
    if (std::abs(m.body_roughness - b.roughness) > 1e-6) {
      p.approximations.push_back(fmt::format(
          "Principled: one Roughness {:.4g} serves the diffuse and the lobe; the fit's Burley "
          "body has r = {:.4g}",
          b.roughness, m.body_roughness));
    }
  } else {
    p.approximations.push_back(fmt::format(
        "Principled: Cycles' diffuse is Burley's (retro-reflection with the shared roughness "
        "{:.4g}, (1 - FL/2)(1 - FV/2) falloff), the fit's {}",
        b.roughness, m.body == Body::kLambert ? "Lambert" : "Oren-Nayar (Fujii)"));
  }
  NoteMasking(m, Masking::kSeparable, "Cycles 3.4 Principled BSDF (GGX)", &p);
  if (worst > 1e-6) {
    p.approximations.push_back(fmt::format(
        "Principled: ks = {} is not grey + a tint of the base colour: cspec0 = {} (channels up to "
        "{:.3g} % off at normal incidence)",
        Fmt3(ks), Fmt3(b.principled_f0), 100 * worst));
  }
  return b;
}

}  // namespace brdfit::exports
