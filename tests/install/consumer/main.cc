// Synthesizes a lambert+ggx table, writes it, loads it back through pipeline::LoadInput, fits
// it, checks the parameters come back and exports the fit as glTF (the export layer): the
// installed headers and libraries work together.
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/synth.h"
#include "export/gltf.h"
#include "export/lobe_material.h"
#include "export/targets.h"
#include "fit/fitter.h"
#include "io/table_io.h"
#include "models/registry.h"
#include "pipeline/inputs.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const brdfit::ModelInfo* m = brdfit::FindModel("lambert+ggx");
  if (!m) return 3;
  const std::vector<double> truth = {0.3, 0.2, 0.1, 0.8, 0.7, 0.6, 0.2};
  brdfit::Grid g;
  g.n_theta_h = 16;
  g.n_theta_d = 16;
  g.n_phi_d = 32;
  const brdfit::Table t = brdfit::SynthesizeTable(
      g, [&](const brdfit::Geometry& geo, double rgb[3]) { m->eval(truth.data(), geo, rgb); }, {});
  brdfit::SaveTable(t, argv[1]);
  const brdfit::Table back = brdfit::pipeline::LoadInput(argv[1]);
  brdfit::FitOptions fo;
  const brdfit::FitResult r = brdfit::FitTable("lambert+ggx", back, brdfit::SampleOptions{}, fo);
  double worst = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) worst = std::fmax(worst, std::fabs(r.params[i] - truth[i]));
  std::printf("status %d, largest parameter error %.3g\n", static_cast<int>(r.status), worst);
  if (r.Failed() || !(worst < 1e-3)) return 1;
  // glTF roughness is sqrt(alpha) (export/targets.h): the export layer saw the fitted alpha.
  const brdfit::exports::GltfPbr pbr = brdfit::exports::ToGltf(brdfit::exports::FromFit(r));
  const brdfit::exports::GltfFiles gltf = brdfit::exports::BuildGltf(pbr, {}, "");
  std::printf("glTF roughness %.4f, %zu bytes of JSON\n", pbr.roughness, gltf.json.size());
  if (!(std::fabs(pbr.roughness - std::sqrt(truth[6])) < 1e-3) || gltf.json.empty()) return 4;
  std::printf("recovered\n");
  return 0;
}
