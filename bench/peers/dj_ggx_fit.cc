// The whole GGX fit of jdupuy/dj_brdf, the fastest peer (docs/fitting.md, "Against the fastest
// peer"): read a MERL table, tabulate its microfacet NDF by power iterations with Smith's
// masking (Dupuy, Heitz, Iehl, Poulin, Ostromoukhov 2015, "Extracting Microfacet-based BRDF
// Parameters from Arbitrary Materials with Power Iterations", EGSR), and fit GGX's alpha to it:
// what `brdfit fit --model ggx` is timed against. Built by bench/peer_dj_brdf.py from a
// dj_brdf.h the user fetched (the header is never part of this repository), through its
// documented API (its examples/merl_params.cpp).
//
//   dj_ggx_fit TABLE.binary...   prints "TABLE alpha" per table
#include <cstdio>

#define DJ_BRDF_IMPLEMENTATION 1
#include "dj_brdf.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s TABLE.binary...\n", argv[0]);
    return 2;
  }
  for (int i = 1; i < argc; ++i) {
    djb::merl merl(argv[i]);
    djb::tabular tab(djb::microfacet::GAF_SMITH, merl, 90, true);
    djb::ggx* ggx = djb::tabular::to_ggx(tab);
    double alpha = 0;
    ggx->get_roughness(&alpha, nullptr, nullptr);
    std::printf("%s %.6f\n", argv[i], alpha);
    delete ggx;
  }
  return 0;
}
