// Fuzz harness: a cached fit of `brdfit render --cache DIR` (io/fit_cache_entry.h,
// ReadFitCacheEntry; fit-<key>.json). Byte 0 picks the model the entry is read for (the
// registry's models in order); the rest is the file. After a successful read: one value per
// parameter of the model, each finite and inside its bounds (1e300 crashed the renderer, issue
// 14 item 5), and writing the entry and reading it back gives the same values bit for bit.
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/model_params.h"
#include "fuzz/harness_util.h"
#include "io/fit_cache_entry.h"
#include "models/registry.h"

namespace brdfit::fuzz {

int FuzzRenderCache(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const ModelInfo& model = AllModels()[in.U8() % AllModels().size()];
  const std::string_view rest = in.Rest();
  const auto path = WriteScratch("fit-entry.json", rest.data(), rest.size());
  std::vector<double> params;
  try {
    params = ReadFitCacheEntry(path, model.name);
  } catch (const InputError&) {
    return 0;
  }
  CheckInvariant(CheckModelParams(model.name, params).empty(),
                 "parameters that are not the model's");
  FitCacheEntry e;
  e.model = model.name;
  e.params = params;
  e.param_names = model.param_names;
  e.status = "converged";
  const std::string text = FitCacheEntryJson(e);
  const auto again = WriteScratch("fit-entry2.json", text.data(), text.size());
  const std::vector<double> back = ReadFitCacheEntry(again, model.name);
  CheckInvariant(back.size() == params.size() &&
                     std::memcmp(back.data(), params.data(), params.size() * sizeof(double)) == 0,
                 "round trip of the parameters");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzRenderCache)
