// Autodiff residual blocks of the catalog models with index % kShards == 2 (fit/model_ops.h).
#include "fit/model_ops_impl.h"

namespace brdfit::internal {
void RegisterModels2(std::vector<ModelOps>& out) {
  RegisterShard<2>(out);
}
}  // namespace brdfit::internal
