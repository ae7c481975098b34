#pragma once
// BRDFIT_ASAN is 1 in code built with AddressSanitizer, by GCC (which defines
// __SANITIZE_ADDRESS__) or by clang (which says so through __has_feature): `make test-asan`
// builds with clang, the fuzz harnesses too.
#if defined(__SANITIZE_ADDRESS__)
#define BRDFIT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BRDFIT_ASAN 1
#endif
#endif
#ifndef BRDFIT_ASAN
#define BRDFIT_ASAN 0
#endif
