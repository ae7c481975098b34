// log1p over an array, for the metrics' hot loop (fit/metrics.cc).
#pragma once

#include <cstddef>

namespace brdfit {

// y[k] = log1p(x[k]) for k < n (x and y may be the same array). Where the CPU has AVX2, four at
// a time by glibc's vector math library (libmvec's _ZGVdN4v_log1p, glibc >= 2.35: within 2 ulp
// of libm's log1p, tested; a third of libm's time); elsewhere libm's log1p one at a time. NaN
// gives NaN either way. The metrics may therefore differ in their last bits between machines
// with and without AVX2 (as libm's own FMA and SSE2 variants may), never between runs or thread
// counts on one machine.
void Log1pAll(const double* x, std::size_t n, double* y);

// True when Log1pAll uses the vector library on this machine.
bool Log1pAllIsVectorized();

}  // namespace brdfit
