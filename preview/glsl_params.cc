#include "preview/glsl_params.h"

#include <cctype>
#include <cstdio>
#include <stdexcept>

#include "preview/glsl_models.h"

namespace brdfit::preview {
namespace {

// GLSL 3.30 §3.7: a letter or underscore, then letters, digits, underscores; "gl_" and "__"
// are reserved.
bool IsGlslIdentifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return s.rfind("gl_", 0) != 0 && s.find("__") == std::string_view::npos;
}

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

std::string GlslParamStructName(const std::string& lobe_name) {
  return GlslFunctionName(lobe_name) + "_params";
}

std::string GlslParamStruct(const std::string& lobe_name, const std::vector<ParamSpec>& params) {
  std::string src = "struct " + GlslParamStructName(lobe_name) + " {\n";
  for (const ParamSpec& p : params) {
    if (!IsGlslIdentifier(p.name)) {
      throw std::invalid_argument("model '" + lobe_name + "': parameter '" + std::string(p.name) +
                                  "' is not a GLSL identifier");
    }
    // Appended piece by piece: GCC 12's -Wrestrict misfires on chains of string operator+.
    src.append("  float ").append(p.name).append(";  // [").append(Number(p.lower));
    src.append(", ").append(Number(p.upper)).append("]");
    if (p.unit != "1") src.append(" ").append(p.unit);
    src.append(": ").append(p.doc).append("\n");
  }
  return src + "};\n";
}

std::string GlslParamConstructor(const std::string& lobe_name, const std::string& uniform,
                                 std::size_t offset, std::size_t count) {
  std::string src = GlslParamStructName(lobe_name) + "(";
  for (std::size_t i = 0; i < count; ++i) {
    src += (i ? ", " : "") + uniform + "[" + std::to_string(offset + i) + "]";
  }
  return src + ")";
}

}  // namespace brdfit::preview
