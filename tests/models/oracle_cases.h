// The oracle of every catalog model (models/catalog.h) and the parameter sets it is checked at.
// The oracles themselves are tests/models/oracles.h: each model written again in its paper's
// form, independent of models/. ModelOracle.* (test_oracles.cc) runs one test per catalog entry;
// an entry whose type has no OracleCase specialization here fails there, with a message saying
// to add one. Sums need none: their oracle is the sum of their lobes' oracles.
#pragma once

#include <cmath>

#include "models/catalog.h"
#include "tests/models/oracles.h"
#include "tests/models/param_sets.h"

namespace brdfit::test {

// Primary template: no oracle (kDefined false).
template <class M>
struct OracleCase {
  static constexpr bool kDefined = false;
};

// A defined case: Eval is the oracle function kOracle.
using OracleFn = void (*)(const double* p, const oracle::Angles& a, double* rgb);
template <OracleFn kOracle>
struct OracleOf {
  static constexpr bool kDefined = true;
  static void Eval(const double* p, const oracle::Angles& a, double* rgb) { kOracle(p, a, rgb); }
};

// The two-form oracles with their form fixed.
inline void WardOracle(const double* p, const oracle::Angles& a, double* rgb) {
  oracle::Ward(p, a, rgb, false);
}
inline void WardDuerOracle(const double* p, const oracle::Angles& a, double* rgb) {
  oracle::Ward(p, a, rgb, true);
}
inline void GgxOracle(const double* p, const oracle::Angles& a, double* rgb) {
  oracle::Ggx(p, a, rgb, false);
}
inline void GgxHcOracle(const double* p, const oracle::Angles& a, double* rgb) {
  oracle::Ggx(p, a, rgb, true);
}

template <>
struct OracleCase<Lambert> : OracleOf<oracle::Lambert> {
  static ParamSets Params() { return {{0.2, 0.5, 0.9}, {1, 1, 1}}; }
};

template <>
struct OracleCase<OrenNayar> : OracleOf<oracle::OrenNayar> {
  static ParamSets Params() { return WithWeights({{0.0}, {0.1}, {0.5}, {1.0}, {oracle::kPi / 2}}); }
};

template <>
struct OracleCase<Burley> : OracleOf<oracle::BurleyFrostbite> {
  static ParamSets Params() { return WithWeights({{1e-4}, {0.01}, {0.25}, {1.0}}); }
};

template <>
struct OracleCase<OrenNayarFujii> : OracleOf<oracle::OrenNayarFujii> {
  // Not sigma = 1: there A (1 + s) at grazing opposite directions (s -> -1) cancels to ~1e-6 of
  // A, and the model's s from vector components and the oracle's from angles differ by a
  // rounding of A (a relative 1e-10 of the tiny value), which the angle conditioning does not
  // measure.
  static ParamSets Params() { return WithWeights({{0.0}, {0.1}, {0.5}, {0.95}}); }
};

template <>
struct OracleCase<Burley2012> : OracleOf<oracle::Burley2012> {
  static ParamSets Params() { return WithWeights({{1e-4}, {0.01}, {0.25}, {1.0}}); }
};

template <>
struct OracleCase<Phong> : OracleOf<oracle::Phong> {
  static ParamSets Params() { return WithWeights({{1}, {3.5}, {40}, {1000}}); }
};

template <>
struct OracleCase<BlinnPhong> : OracleOf<oracle::BlinnPhong> {
  static ParamSets Params() { return WithWeights({{1}, {3.5}, {40}, {1000}}); }
};

template <>
struct OracleCase<Ward> : OracleOf<WardOracle> {
  static ParamSets Params() { return WithWeights({{0.005}, {0.05}, {0.3}, {1.0}}); }
};

template <>
struct OracleCase<WardDuer> : OracleOf<WardDuerOracle> {
  static ParamSets Params() { return OracleCase<Ward>::Params(); }
};

template <>
struct OracleCase<Ggx> : OracleOf<GgxOracle> {
  static ParamSets Params() { return WithWeights({{1e-4}, {1e-3}, {0.01}, {0.1}, {0.5}, {1.0}}); }
};

template <>
struct OracleCase<GgxHc> : OracleOf<GgxHcOracle> {
  static ParamSets Params() { return OracleCase<Ggx>::Params(); }
};

template <>
struct OracleCase<GgxF0> : OracleOf<oracle::GgxF0> {
  static ParamSets Params() {
    ParamSets params;
    for (double alpha : {1e-4, 1e-2, 0.1, 0.5, 1.0}) {
      params.push_back({0.04, 0.04, 0.04, alpha});
      params.push_back({1e-3, 0.5, 1.0, alpha});  // F0 = 0 exactly: F = 0 at retro
      params.push_back({0.95, 0.64, 0.54, alpha});
    }
    return params;
  }
};

template <>
struct OracleCase<Abc> : OracleOf<oracle::Abc> {
  static ParamSets Params() {
    ParamSets shapes;
    for (double b : {1e-2, 10.0, 1e4, 1e8})
      for (double c : {0.05, 1.0, 8.0}) shapes.push_back({b, c, 0.3});
    shapes.push_back({100.0, 1.5, 1e-3});  // F0 = 0 exactly: F = 0 at retro
    shapes.push_back({100.0, 1.5, 1.0});
    return WithWeights(shapes);
  }
};

template <>
struct OracleCase<Sgd> : OracleOf<oracle::Sgd> {
  static ParamSets Params() {
    ParamSets shapes;
    for (double alpha : {1e-4, 1e-2, 0.3, 1.0})
      for (double pw : {0.0, 0.5, 1.2, 2.0}) shapes.push_back({alpha, pw, 0.2});
    return WithWeights(shapes);
  }
};

template <>
struct OracleCase<Sheen> : OracleOf<oracle::Sheen> {
  static ParamSets Params() { return WithWeights({{0.01}, {0.07}, {0.3}, {1.0}}); }
};

template <>
struct OracleCase<Beckmann> : OracleOf<oracle::Beckmann> {
  static ParamSets Params() { return WithWeights({{1e-4}, {0.01}, {0.1}, {0.5}, {1.0}}); }
};

template <>
struct OracleCase<CookTorrance> : OracleOf<oracle::CookTorrance> {
  static ParamSets Params() {
    return WithWeights({{0.01, 0.0}, {0.1, 0.04}, {0.5, 0.9}, {1.0, 0.3}});
  }
};

template <>
struct OracleCase<Lafortune> : OracleOf<oracle::Lafortune> {
  static ParamSets Params() {
    ParamSets shapes;
    for (double cxy : {-19.5, -1.46, -1.0, -0.5, 0.0, 0.7, 1.1, 25.0})
      for (double n : {1.0, 4.5, 60.0, 800.0}) shapes.push_back({cxy, n});
    return WithWeights(shapes);
  }
};

template <>
struct OracleCase<Ue4> : OracleOf<oracle::Ue4> {
  static ParamSets Params() {
    ParamSets params;
    for (double m : {0.0, 0.4, 1.0})
      for (double alpha : {0.1, 0.4, 1.0}) params.push_back({0.2, 0.5, 0.9, m, alpha});
    return params;
  }
};

// A sum: the lobes' oracles added, at the lobes' sets joined (JoinLobeSets).
template <class... L>
struct OracleCase<Sum<L...>> {
  static constexpr bool kDefined = (OracleCase<L>::kDefined && ...);
  static ParamSets Params() { return JoinLobeSets({OracleCase<L>::Params()...}); }
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
