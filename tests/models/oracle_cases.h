// The oracle of every catalog model (models/catalog.h) and the parameter sets it is checked at.
// The oracles themselves are tests/models/oracles.h: each model written again in its paper's
// form, independent of models/. ModelOracle.* (test_oracles.cc) runs one test per catalog entry;
// an entry whose type has no OracleCase specialization here fails there, with a message saying
// to add one. Sums need none: their oracle is the sum of their lobes' oracles.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "models/catalog.h"
#include "tests/models/oracles.h"

namespace brdfit::test {

using ParamSets = std::vector<std::vector<double>>;

// Parameter vectors: RGB weights (0.2, 0.5, 0.9) followed by each shape tuple.
inline ParamSets WithWeights(const ParamSets& shapes) {
  ParamSets out;
  for (const auto& s : shapes) {
    std::vector<double> p = {0.2, 0.5, 0.9};
    p.insert(p.end(), s.begin(), s.end());
    out.push_back(p);
  }
  return out;
}

// Primary template: no oracle (kDefined false).
template <class M>
struct OracleCase {
  static constexpr bool kDefined = false;
};

struct DefinedOracle {
  static constexpr bool kDefined = true;
};

template <>
struct OracleCase<Lambert> : DefinedOracle {
  static ParamSets Params() { return {{0.2, 0.5, 0.9}, {1, 1, 1}}; }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Lambert(p, a, rgb);
  }
};

template <>
struct OracleCase<OrenNayar> : DefinedOracle {
  static ParamSets Params() { return WithWeights({{0.0}, {0.1}, {0.5}, {1.0}, {oracle::kPi / 2}}); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::OrenNayar(p, a, rgb);
  }
};

template <>
struct OracleCase<Burley> : DefinedOracle {
  static ParamSets Params() { return WithWeights({{1e-4}, {0.01}, {0.25}, {1.0}}); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::BurleyFrostbite(p, a, rgb);
  }
};

template <>
struct OracleCase<Phong> : DefinedOracle {
  static ParamSets Params() { return WithWeights({{1}, {3.5}, {40}, {1000}}); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Phong(p, a, rgb);
  }
};

template <>
struct OracleCase<BlinnPhong> : DefinedOracle {
  static ParamSets Params() { return WithWeights({{1}, {3.5}, {40}, {1000}}); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::BlinnPhong(p, a, rgb);
  }
};

template <>
struct OracleCase<Ward> : DefinedOracle {
  static ParamSets Params() { return WithWeights({{0.005}, {0.05}, {0.3}, {1.0}}); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Ward(p, a, rgb, false);
  }
};

template <>
struct OracleCase<WardDuer> : DefinedOracle {
  static ParamSets Params() { return OracleCase<Ward>::Params(); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Ward(p, a, rgb, true);
  }
};

template <>
struct OracleCase<Ggx> : DefinedOracle {
  static ParamSets Params() { return WithWeights({{1e-4}, {1e-3}, {0.01}, {0.1}, {0.5}, {1.0}}); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Ggx(p, a, rgb, false);
  }
};

template <>
struct OracleCase<GgxHc> : DefinedOracle {
  static ParamSets Params() { return OracleCase<Ggx>::Params(); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Ggx(p, a, rgb, true);
  }
};

template <>
struct OracleCase<Beckmann> : DefinedOracle {
  static ParamSets Params() { return WithWeights({{1e-4}, {0.01}, {0.1}, {0.5}, {1.0}}); }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Beckmann(p, a, rgb);
  }
};

template <>
struct OracleCase<CookTorrance> : DefinedOracle {
  static ParamSets Params() {
    return WithWeights({{0.01, 0.0}, {0.1, 0.04}, {0.5, 0.9}, {1.0, 0.3}});
  }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::CookTorrance(p, a, rgb);
  }
};

template <>
struct OracleCase<Lafortune> : DefinedOracle {
  static ParamSets Params() {
    ParamSets shapes;
    for (double cxy : {-19.5, -1.46, -1.0, -0.5, 0.0, 0.7, 1.1, 25.0})
      for (double n : {1.0, 4.5, 60.0, 800.0}) shapes.push_back({cxy, n});
    return WithWeights(shapes);
  }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Lafortune(p, a, rgb);
  }
};

template <>
struct OracleCase<Ue4> : DefinedOracle {
  static ParamSets Params() {
    ParamSets params;
    for (double m : {0.0, 0.4, 1.0})
      for (double alpha : {0.1, 0.4, 1.0}) params.push_back({0.2, 0.5, 0.9, m, alpha});
    return params;
  }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    oracle::Ue4(p, a, rgb);
  }
};

// A sum: the lobes' oracles added. Its k-th parameter set joins lobe i's set (k + i) mod (its
// count), so every set of every lobe appears and repeated lobes differ.
template <class... L>
struct OracleCase<Sum<L...>> {
  static constexpr bool kDefined = (OracleCase<L>::kDefined && ...);
  static ParamSets Params() {
    const std::vector<ParamSets> lobes = {OracleCase<L>::Params()...};
    std::size_t count = 0;
    for (const auto& s : lobes) count = std::max(count, s.size());
    ParamSets out(count);
    for (std::size_t k = 0; k < count; ++k)
      for (std::size_t i = 0; i < lobes.size(); ++i) {
        const auto& p = lobes[i][(k + i) % lobes[i].size()];
        out[k].insert(out[k].end(), p.begin(), p.end());
      }
    return out;
  }
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) {
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    (
        [&] {
          double lobe[3];
          OracleCase<L>::Eval(p, a, lobe);
          for (int c = 0; c < 3; ++c) rgb[c] += lobe[c];
          p += kNumParams<L>;
        }(),
        ...);
  }
};

}  // namespace brdfit::test
