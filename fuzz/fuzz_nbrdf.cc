// Fuzz harness: NBRDF weights in a zip archive (io/nbrdf.h). The first byte picks a mode:
//  * bit 0 clear: the rest is the archive itself: ListNbrdfMaterials, then ReadNbrdf of the
//    first two listed materials (libzip directory and member parsing, declared sizes);
//  * bit 0 set:   the rest is one member's HDF5 image, stored uncompressed as
//    merl_nbrdf/m.h5 in a well-formed archive built here: ReadNbrdf(zip, "m") (the network
//    layout checks: dataset names, shapes, types, finite weights).
// A network that reads must evaluate and tabulate on a small grid: outputs finite (else an
// InputError naming the source), valid cells non-negative after the documented clamping,
// below-horizon cells masked.
#include <cmath>
#include <string>
#include <vector>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/nbrdf.h"

namespace brdfit::fuzz {

namespace {

void CheckNetwork(const NbrdfNetwork& net) {
  const auto h1 = net.k1.cols(), h2 = net.k2.cols();
  CheckInvariant(net.k1.rows() == 6 && h1 > 0 && h2 > 0, "layer 1 shape");
  CheckInvariant(net.b1.size() == h1 && net.k2.rows() == h1 && net.b2.size() == h2,
                 "layer 2 shape");
  CheckInvariant(net.k3.rows() == h2 && net.k3.cols() == 3 && net.b3.size() == 3,
                 "layer 3 shape");
  CheckInvariant(net.k1.allFinite() && net.k2.allFinite() && net.k3.allFinite() &&
                     net.b1.allFinite() && net.b2.allFinite() && net.b3.allFinite(),
                 "non-finite weight accepted");

  Grid g;
  g.n_theta_h = 3;
  g.n_theta_d = 3;
  g.n_phi_d = 4;
  NbrdfTabulation tab;
  try {
    tab = TabulateNbrdf(net, g);
  } catch (const InputError&) {
    return;  // weights that overflow exp(y): rejected with the source named
  }
  const Table& t = tab.table;
  CheckInvariant(t.rgb.size() == 3 * g.NumCells() && t.valid.size() == g.NumCells(), "sizes");
  std::size_t masked = 0;
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    CheckInvariant(t.valid[i] == (g.CellAboveHorizon(i) ? 1 : 0), "horizon mask");
    masked += !t.valid[i];
    if (!t.valid[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double v = t.rgb[3 * i + c];
      if (!(std::isfinite(v) && v >= 0)) Violation("tabulated value " + std::to_string(v));
    }
  }
  CheckInvariant(masked == tab.below_horizon, "below_horizon count");
}

void ReadAndCheck(const std::filesystem::path& zip, const std::string& material) {
  NbrdfNetwork net;
  try {
    net = ReadNbrdf(zip, material);
  } catch (const InputError&) {
    return;
  }
  CheckNetwork(net);
}

}  // namespace

int FuzzNbrdf(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const bool member_mode = in.U8() & 1;
  const std::string_view rest = in.Rest();
  if (member_mode) {
    ReadAndCheck(WriteNbrdfZip("nbrdf-built.zip", rest), "m");
    return 0;
  }
  const auto zip = WriteScratch("nbrdf-in.zip", rest.data(), rest.size());
  std::vector<std::string> materials;
  try {
    materials = ListNbrdfMaterials(zip);
  } catch (const InputError&) {
    return 0;
  }
  for (std::size_t i = 0; i < materials.size() && i < 2; ++i) ReadAndCheck(zip, materials[i]);
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzNbrdf)
