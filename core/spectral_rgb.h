// Spectral reflectance samples -> linear sRGB: the one convention brdfit uses for spectral
// measurements (the spectral `.bsdf` files of the RGL database).
//
//  * Observer: CIE 1931 2° colour-matching functions, as the multi-lobe piecewise-Gaussian fit
//    of Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color
//    Matching Functions", JCGT 2(2), Eq. 2 (within ~1 % of the tabulated functions' peak).
//  * Illuminant: equal-energy E (a reflectance is converted, not a light).
//  * Colour space: XYZ -> linear sRGB by the IEC 61966-2-1 matrix, then each channel divided by
//    that of a constant spectrum of 1 over the same samples, so that a perfect white reflector
//    is (1, 1, 1) (a von Kries white balance in sRGB's primaries, from E to sRGB's white).
//  * Integration: the trapezoid rule over the given wavelengths (nm), which must be strictly
//    increasing; outside them the spectrum counts as zero.
#pragma once

#include <array>
#include <vector>

namespace brdfit {

// CIE 1931 x-bar, y-bar, z-bar at lambda (nm): Wyman et al. 2013, Eq. 2.
std::array<double, 3> Cie1931Xyz(double lambda_nm);

// Weights w[c][k] such that channel c = sum_k w[c][k] S(lambda_k). Requires at least two
// strictly increasing wavelengths whose span reaches some of the visible range.
std::array<std::vector<double>, 3> SrgbWeights(const std::vector<double>& wavelengths_nm);

// The way back, for writing spectral files: three spectra B_c on `wavelengths` with
// SrgbWeights(B_c) = the unit vector e_c, so that sum_c rgb_c B_c converts back to rgb exactly.
// They start as box-like bands (blue below 490-510 nm, red above 580-600 nm, green between,
// linear ramps: a partition of unity) and are mixed by the inverse of their 3 x 3 sRGB image.
// Their sum stays the constant 1 (the bands sum to 1 and white maps to white), so a grey is a
// flat spectrum and renders the same under any illuminant; saturated primaries dip a few per
// cent below zero in the other bands (min -0.05), which a writer clamps and counts.
std::array<std::vector<double>, 3> SrgbBasisSpectra(const std::vector<double>& wavelengths_nm);

}  // namespace brdfit
