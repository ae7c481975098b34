#include "fit/fast_cbrt.h"

namespace brdfit {

#if defined(__x86_64__) && defined(__has_attribute)
#if __has_attribute(target_clones)
__attribute__((target_clones("avx2", "default")))
#endif
#endif
void FastCbrtRefineAll(const double* x, std::size_t n, double* y) {
  for (std::size_t k = 0; k < n; ++k) y[k] = FastCbrtRefine(x[k], y[k]);
}

}  // namespace brdfit
