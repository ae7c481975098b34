// Scalar helpers shared by the GLSL twins (twin of models/math.h). GLSL has no log1p or erfc.

float brdfit_Pow5(float x) {
  float x2 = x * x;
  return x2 * x2 * x;
}

// log(1 + x) for x > -1. log(1 + x) in float loses the digits of small x (1 + x rounds at
// 6e-8), which exponents up to 1e5 would amplify; |x| < 0.1 uses the Taylor series
// x - x^2/2 + ... (11 terms: truncation < 0.1^12 / 12, below float rounding).
float brdfit_Log1p(float x) {
  if (abs(x) >= 0.1) return log(1.0 + x);
  float s = 0.0;
  for (int k = 11; k >= 1; --k) s = 1.0 / float(k) - x * s;
  return x * s;
}

// cos(theta)^n from sin^2(theta): exp(n/2 log1p(-sin2)) (twin of PowCos near the pole).
float brdfit_PowCosFromSin2(float sin2, float n) {
  if (sin2 >= 1.0) return 0.0;
  return exp(0.5 * n * brdfit_Log1p(-sin2));
}

// Complementary error function with fractional error < 1.2e-7 everywhere: Press, Teukolsky,
// Vetterling, Flannery, "Numerical Recipes in C" 2nd ed. (1992), §6.2, erfcc (Chebyshev fit).
float brdfit_Erfc(float x) {
  float z = abs(x);
  float t = 1.0 / (1.0 + 0.5 * z);
  float r = t * exp(-z * z - 1.26551223 +
                    t * (1.00002368 +
                    t * (0.37409196 +
                    t * (0.09678418 +
                    t * (-0.18628806 +
                    t * (0.27886807 +
                    t * (-1.13520398 +
                    t * (1.48851587 +
                    t * (-0.82215223 +
                    t * 0.17087277)))))))));
  return x >= 0.0 ? r : 2.0 - r;
}
