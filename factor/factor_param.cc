#include "factor/factor_param.h"

#include "core/error.h"

namespace brdfit {

const char* MapFormula(FactorMap m) {
  switch (m) {
    case FactorMap::kDiskParabolic:
      return "hemisphere disk map, parabolic: (s,t) = (x,y)/(1+z) = tan(theta/2) (cos phi, "
             "sin phi); N x N texels, column i at s = -1+(2i+1)/N, row j at t = -1+(2j+1)/N; "
             "texels with s^2+t^2 > 1 hold the rim value; bilinear, clamp to edge";
    case FactorMap::kDiskSqrtTheta:
      return "hemisphere disk map, sqrt-theta: (s,t) = sqrt(theta/(pi/2)) (cos phi, sin phi); "
             "N x N texels, column i at s = -1+(2i+1)/N, row j at t = -1+(2j+1)/N; texels with "
             "s^2+t^2 > 1 hold the rim value; bilinear, clamp to edge";
    case FactorMap::kThetaDPhiD:
      return "Rusinkiewicz difference angles: column i at theta_d = (i+1/2)/W pi/2 (clamp to "
             "edge), row j at phi_d = (j+1/2)/H pi (repeat: period pi); bilinear";
  }
  return "?";
}

const FactorParamSpec& GetFactorParamSpec(FactorParam p) {
  // McCool, Ang, Ahmad 2001: the reciprocal form with the half vector.
  static const FactorParamSpec kMcCool{FactorParam::kMcCool,
                                       "f(wi,wo) = p(wi) q(wh) p(wo)",
                                       {FactorMap::kDiskParabolic, "wi and wo", "1"},
                                       {FactorMap::kDiskSqrtTheta, "wh", "1/sr"},
                                       2,
                                       "p(normal) = 1 per channel (log p = 0 at theta = 0)"};
  // Kautz & McCool 1999: half-angle / difference parameterization.
  static const FactorParamSpec kHalfDiff{
      FactorParam::kHalfDiff,
      "f(wi,wo) = p(wh) q(theta_d, phi_d)",
      {FactorMap::kDiskSqrtTheta, "wh", "1/sr"},
      {FactorMap::kThetaDPhiD, "(theta_d, phi_d)", "1"},
      1,
      "q(theta_d -> 0) = 1 per channel (mean of log q over the first theta_d column is 0)"};
  return p == FactorParam::kMcCool ? kMcCool : kHalfDiff;
}

}  // namespace brdfit
