#include "preview/glsl_models.h"

#include <optional>
#include <stdexcept>
#include <type_traits>

#include "core/error.h"
#include "core/suggest.h"
#include "models/catalog.h"
#include "models/registry.h"
#include "preview/glsl_microfacet.h"
#include "preview/glsl_params.h"
#include "preview/glsl_sources.h"

namespace brdfit::preview {
namespace {

template <class M>
struct LobesOf {
  static void Append(std::vector<GlslLobe>* out) {
    const std::size_t offset = out->empty() ? 0 : out->back().offset + out->back().count;
    const std::string name(M::kName);
    GlslLobe lobe;
    lobe.name = name;
    lobe.function = GlslFunctionName(name);
    lobe.params_struct = GlslParamStructName(name);
    for (const ParamSpec& p : M::kParams) lobe.param_names.emplace_back(p.name);
    lobe.param_block =
        GlslParamStruct(name, std::vector<ParamSpec>(M::kParams.begin(), M::kParams.end()));
    if constexpr (MicrofacetLobe<M>) {
      lobe.file = "models/glsl/microfacet.glsl";
      lobe.entry_point = GlslMicrofacetEntryPoint<M>(lobe.function, lobe.params_struct);
    } else {
      lobe.file = "models/glsl/" + name + ".glsl";
    }
    lobe.offset = offset;
    lobe.count = kNumParams<M>;
    out->push_back(std::move(lobe));
  }
};
template <class... L>
struct LobesOf<Sum<L...>> {
  static void Append(std::vector<GlslLobe>* out) { (LobesOf<L>::Append(out), ...); }
};

}  // namespace

std::string GlslFunctionName(const std::string& lobe_name) {
  std::string f = "brdfit_";
  for (char c : lobe_name) f += (c == '-' || c == ':' || c == '+') ? '_' : c;
  return f;
}

std::vector<GlslLobe> GlslLobes(const std::string& model_name) {
  std::optional<std::vector<GlslLobe>> found;
  ForEachModel([&](auto m) {
    using M = typename decltype(m)::type;
    if (!found && ModelName<M>() == model_name) {
      std::vector<GlslLobe> lobes;
      LobesOf<M>::Append(&lobes);
      found = std::move(lobes);
    }
  });
  if (!found) {
    throw InputError("unknown model '" + model_name + "'" +
                     SuggestionAfter(model_name, AllModelNames()) + " (known: " + ModelNames() +
                     ")");
  }
  for (const auto& lobe : *found) {
    bool embedded = false;
    for (const auto& f : EmbeddedGlsl()) embedded |= f.path == lobe.file;
    if (!embedded) {
      throw std::runtime_error("model '" + model_name + "': no GLSL twin " + lobe.file);
    }
  }
  return *found;
}

}  // namespace brdfit::preview
