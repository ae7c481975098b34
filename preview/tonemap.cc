#include "preview/tonemap.h"

#include "core/error.h"

namespace brdfit::preview {

ToneMap ToneMapFromString(const std::string& s) {
  if (s == "linear") return ToneMap::kLinear;
  if (s == "reinhard") return ToneMap::kReinhard;
  if (s == "uncharted2") return ToneMap::kUncharted2;
  if (s == "cineon") return ToneMap::kCineon;
  throw InputError("unknown tone map '" + s + "' (expected linear, reinhard, uncharted2, cineon)");
}

Encoding EncodingFromString(const std::string& s) {
  if (s == "linear") return Encoding::kLinear;
  if (s == "srgb") return Encoding::kSrgb;
  if (s == "gamma2") return Encoding::kGamma2;
  throw InputError("unknown output encoding '" + s + "' (expected srgb, gamma2, linear)");
}

const char* ToString(ToneMap t) {
  switch (t) {
    case ToneMap::kLinear: return "linear";
    case ToneMap::kReinhard: return "reinhard";
    case ToneMap::kUncharted2: return "uncharted2";
    case ToneMap::kCineon: return "cineon";
  }
  return "?";
}

const char* ToString(Encoding e) {
  switch (e) {
    case Encoding::kLinear: return "linear";
    case Encoding::kSrgb: return "srgb";
    case Encoding::kGamma2: return "gamma2";
  }
  return "?";
}

}  // namespace brdfit::preview
