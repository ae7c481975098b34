// Autodiff residual blocks of the catalog models with index % kShards == 1 (fit/model_ops.h).
#include "fit/model_ops_impl.h"

namespace brdfit::internal {
void RegisterModels1(std::vector<ModelOps>& out) {
  RegisterShard<1>(out);
}
}  // namespace brdfit::internal
