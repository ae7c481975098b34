// Autodiff residual blocks of the catalog models with index % kShards == 0 (fit/model_ops.h).
#include "fit/model_ops_impl.h"

namespace brdfit::internal {
void RegisterModels0(std::vector<ModelOps>& out) {
  RegisterShard<0>(out);
}
}  // namespace brdfit::internal
