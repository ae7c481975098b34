#include "export/scene_text.h"

#include <fmt/core.h>

#include <algorithm>

#include "export/comment_text.h"

namespace brdfit::exports {

namespace {

// Text safe inside an XML comment and a pbrt '#' comment: printable ASCII, no "--".
std::string CommentSafe(const std::string& s) {
  std::string out;
  for (const char ch : CommentText(s)) {
    if (ch == '-' && !out.empty() && out.back() == '-') out += ' ';  // XML: no "--" inside
    out += ch;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

// A character a pbrt string holds as it is: printable ASCII but '"' and '\\'.
bool PbrtChar(char ch) {
  const unsigned char c = static_cast<unsigned char>(ch);
  return c >= 0x20 && c < 0x7f && ch != '"' && ch != '\\';
}

// A string value for pbrt ("..." without quotes or newlines).
std::string PbrtString(const std::string& s) {
  std::string out;
  for (const char ch : s) out += PbrtChar(ch) ? ch : '_';
  return out;
}

// An XML attribute value (between double quotes).
std::string XmlAttribute(const std::string& s) {
  std::string out;
  for (const char ch : s) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

std::string Rgb3(const Rgb& v, const char* sep) {
  return fmt::format("{:.9g}{}{:.9g}{}{:.9g}", v[0], sep, v[1], sep, v[2]);
}

// A Mitsuba 3 roughconductor element (GGX, no Fresnel: material "none"), indented by `in`.
std::string RoughConductor(double alpha, const Rgb& reflectance, const std::string& in) {
  return fmt::format(
      "{0}<bsdf type=\"roughconductor\">\n"
      "{0}  <string name=\"distribution\" value=\"ggx\"/>\n"
      "{0}  <float name=\"alpha\" value=\"{1:.9g}\"/>\n"
      "{0}  <string name=\"material\" value=\"none\"/>\n"
      "{0}  <rgb name=\"specular_reflectance\" value=\"{2}\"/>\n{0}</bsdf>\n",
      in, alpha, Rgb3(reflectance, ", "));
}

// <scene>, the integrator and the sensor every Mitsuba 3 export shares (the material follows).
std::string MitsubaFrameOpen() {
  std::string s;
  s += "<scene version=\"3.0.0\">\n";
  s += "  <integrator type=\"path\">\n    <integer name=\"max_depth\" value=\"3\"/>\n"
       "  </integrator>\n";
  s += "  <sensor type=\"perspective\">\n    <float name=\"fov\" value=\"30\"/>\n"
       "    <transform name=\"to_world\">\n"
       "      <lookat origin=\"0, 0, 4.2\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>\n"
       "    </transform>\n"
       "    <sampler type=\"independent\">\n      <integer name=\"sample_count\" value=\"64\"/>\n"
       "    </sampler>\n"
       "    <film type=\"hdrfilm\">\n      <integer name=\"width\" value=\"256\"/>\n"
       "      <integer name=\"height\" value=\"256\"/>\n    </film>\n  </sensor>\n";
  return s;
}

// The sphere with the material "brdfit-material", the light, </scene>.
std::string MitsubaFrameClose() {
  std::string s;
  s += "  <shape type=\"sphere\">\n    <ref id=\"brdfit-material\"/>\n  </shape>\n";
  s += "  <emitter type=\"directional\">\n    <vector name=\"direction\" value=\"-1, -1, -1\"/>\n"
       "    <rgb name=\"irradiance\" value=\"3, 3, 3\"/>\n  </emitter>\n";
  s += "</scene>\n";
  return s;
}

// The camera, film, sampler, integrator and light every pbrt-v4 export shares.
std::string PbrtFrame(const std::string& image_name) {
  std::string s;
  // pbrt-v4's LookAt puts Cross(up, dir) on the image's right: a left-handed view, the mirror
  // image of the other exports' and brdfit's preview. Scale -1 1 1 (applied to the camera
  // transform) mirrors it back, so that the light from (1, 1, 1) lights the upper right.
  s += "Scale -1 1 1\n";
  s += "LookAt 0 0 4.2  0 0 0  0 1 0\n";
  s += "Camera \"perspective\" \"float fov\" [ 30 ]\n";
  s += fmt::format(
      "Film \"rgb\" \"integer xresolution\" [ 256 ] \"integer yresolution\" [ 256 ]\n"
      "    \"string filename\" [ \"{}\" ]\n",
      PbrtString(image_name));
  s += "Sampler \"zsobol\" \"integer pixelsamples\" [ 64 ]\n";
  s += "Integrator \"volpath\" \"integer maxdepth\" [ 3 ]\n\n";
  s += "WorldBegin\n\n";
  s += "LightSource \"distant\" \"point3 from\" [ 1 1 1 ] \"point3 to\" [ 0 0 0 ]\n"
       "    \"rgb L\" [ 3 3 3 ]\n\n";
  return s;
}

}  // namespace

std::string MitsubaScene(const MitsubaBlend& b, const Provenance& p) {
  std::string s = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!--\n";
  for (const std::string& line : p.Lines()) s += "  " + CommentSafe(line) + "\n";
  s += "  Material: blendbsdf(weight w) of diffuse(R) and roughconductor(ggx, alpha,\n"
       "  material=none, specular_reflectance S) = (1 - w) R / pi + w S D G1 G1 / (4 cos_i cos_o)";
  s += b.second ? ";\n  two lobes: the roughconductor is a blendbsdf(v) of two, (1 - w) R / pi +\n"
                  "  w ((1 - v) S lobe + v S2 lobe2).\n"
                : ".\n";
  if (b.body == Body::kBurley2012) {
    s += "  The body is principled(base_color R, roughness r, specular 0, metallic 0) in place of\n"
         "  diffuse: with specular 0 (eta 1) its specular lobe is 0 and it is Burley 2012's\n"
         "  diffuse R / pi ((1 - FL/2)(1 - FO/2) + RR (FL + FO + FL FO (RR - 1))), RR = 2 r "
         "cos_d^2;\n"
         "  main_specular_sampling_rate 0 samples its diffuse alone.\n";
  }
  s += "  Render: mitsuba -m scalar_rgb this.xml (docs/exports.md)\n-->\n";
  s += MitsubaFrameOpen();
  s += fmt::format(
      "  <bsdf type=\"blendbsdf\" id=\"brdfit-material\">\n"
      "    <float name=\"weight\" value=\"{:.9g}\"/>\n",
      b.weight);
  if (b.body == Body::kBurley2012) {
    s += fmt::format(
        "    <bsdf type=\"principled\">\n      <rgb name=\"base_color\" value=\"{}\"/>\n"
        "      <float name=\"roughness\" value=\"{:.9g}\"/>\n"
        "      <float name=\"specular\" value=\"0\"/>\n"
        "      <float name=\"metallic\" value=\"0\"/>\n"
        "      <float name=\"main_specular_sampling_rate\" value=\"0\"/>\n    </bsdf>\n",
        Rgb3(b.diffuse_reflectance, ", "), b.body_roughness);
  } else {
    s += fmt::format(
        "    <bsdf type=\"diffuse\">\n      <rgb name=\"reflectance\" value=\"{}\"/>\n"
        "    </bsdf>\n",
        Rgb3(b.diffuse_reflectance, ", "));
  }
  if (b.second) {
    s += fmt::format(
        "    <bsdf type=\"blendbsdf\">\n      <float name=\"weight\" value=\"{:.9g}\"/>\n"
        "{}{}    </bsdf>\n",
        b.second->weight, RoughConductor(b.alpha, b.specular_reflectance, "      "),
        RoughConductor(b.second->alpha, b.second->specular_reflectance, "      "));
  } else {
    s += RoughConductor(b.alpha, b.specular_reflectance, "    ");
  }
  s += "  </bsdf>\n";
  s += MitsubaFrameClose();
  return s;
}

std::string PbrtScene(const PbrtMix& m, const Provenance& p, const std::string& image_name) {
  std::string s;
  for (const std::string& line : p.Lines()) s += "# " + CommentSafe(line) + "\n";
  s += "# Material: mix(amount a) of diffuse(R) and conductor(reflectance r, roughness alpha,\n"
       "# remaproughness false) = (1 - a) R / pi + a F_r D G / (4 cos_i cos_o)";
  s += m.second ? ";\n# two lobes: brdfit-specular is a mix(amount v) of two conductors, (1 - a) R "
                  "/ pi +\n"
                  "# a ((1 - v) F_r D G / (4 cos_i cos_o) + v F_r2 D2 G2 / (4 cos_i cos_o)).\n"
                : ".\n";
  s += "# Render: pbrt this.pbrt (docs/exports.md)\n\n";
  s += PbrtFrame(image_name);
  s += fmt::format(
      "MakeNamedMaterial \"brdfit-diffuse\" \"string type\" [ \"diffuse\" ]\n"
      "    \"rgb reflectance\" [ {} ]\n",
      Rgb3(m.diffuse_reflectance, " "));
  const auto conductor = [](const char* name, const Rgb& r, double roughness) {
    return fmt::format(
        "MakeNamedMaterial \"{}\" \"string type\" [ \"conductor\" ]\n"
        "    \"rgb reflectance\" [ {} ]\n"
        "    \"float roughness\" [ {:.9g} ] \"bool remaproughness\" [ false ]\n",
        name, Rgb3(r, " "), roughness);
  };
  if (m.second) {
    s += conductor("brdfit-specular-1", m.conductor_reflectance, m.roughness);
    s += conductor("brdfit-specular-2", m.second->conductor_reflectance, m.second->roughness);
    s += fmt::format(
        "MakeNamedMaterial \"brdfit-specular\" \"string type\" [ \"mix\" ]\n"
        "    \"string materials\" [ \"brdfit-specular-1\" \"brdfit-specular-2\" ]\n"
        "    \"float amount\" [ {:.9g} ]\n",
        m.second->amount);
  } else {
    s += conductor("brdfit-specular", m.conductor_reflectance, m.roughness);
  }
  s += fmt::format(
      "MakeNamedMaterial \"brdfit-material\" \"string type\" [ \"mix\" ]\n"
      "    \"string materials\" [ \"brdfit-diffuse\" \"brdfit-specular\" ]\n"
      "    \"float amount\" [ {:.9g} ]\n\n",
      m.amount);
  s += "AttributeBegin\n  NamedMaterial \"brdfit-material\"\n"
       "  Shape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n";
  return s;
}

bool PbrtStringHolds(const std::string& s) {
  return std::all_of(s.begin(), s.end(), PbrtChar);
}

std::string MitsubaMeasuredScene(const std::string& bsdf_name,
                                 const std::vector<std::string>& header) {
  std::string s = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!--\n";
  for (const std::string& line : header) s += "  " + CommentSafe(line) + "\n";
  s += "  Material: measured (the RGL .bsdf beside this file, Dupuy & Jakob 2018).\n"
       "  Render: mitsuba -m scalar_spectral this.xml (docs/exports.md)\n-->\n";
  s += MitsubaFrameOpen();
  s += fmt::format(
      "  <bsdf type=\"measured\" id=\"brdfit-material\">\n"
      "    <string name=\"filename\" value=\"{}\"/>\n  </bsdf>\n",
      XmlAttribute(bsdf_name));
  s += MitsubaFrameClose();
  return s;
}

std::string PbrtMeasuredScene(const std::string& bsdf_name, const std::vector<std::string>& header,
                              const std::string& image_name) {
  std::string s;
  for (const std::string& line : header) s += "# " + CommentSafe(line) + "\n";
  s += "# Material: measured (the RGL .bsdf beside this file, Dupuy & Jakob 2018).\n";
  s += "# Render: pbrt this.pbrt (docs/exports.md)\n\n";
  s += PbrtFrame(image_name);
  s += fmt::format(
      "MakeNamedMaterial \"brdfit-material\" \"string type\" [ \"measured\" ]\n"
      "    \"string filename\" [ \"{}\" ]\n\n",
      PbrtString(bsdf_name));
  s += "AttributeBegin\n  NamedMaterial \"brdfit-material\"\n"
       "  Shape \"sphere\" \"float radius\" [ 1 ]\nAttributeEnd\n";
  return s;
}

}  // namespace brdfit::exports
