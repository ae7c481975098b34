// Shared by the fuzz harnesses (fuzz/fuzz_<reader>.cc) and by the regression test that replays
// their inputs in the normal build (tests/reliability/test_fuzz_regressions.cc).
//
// A harness is a function  int Fuzz<Reader>(const uint8_t* data, size_t size)  that turns the
// bytes into one or more files, runs the real reader on them, and then checks what came back:
//  * bad input must end in brdfit::InputError (caught here, the expected outcome);
//  * anything else escaping the reader (std::bad_alloc, std::out_of_range, a library exception,
//    a crash, a sanitizer report) is a finding;
//  * a successful read must satisfy the format's invariants (CheckInvariant) and survive a
//    write -> read round trip unchanged.
// With -DBRDFIT_LIBFUZZER the macro BRDFIT_FUZZ_ENTRY defines LLVMFuzzerTestOneInput.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace brdfit::fuzz {

// A violated invariant after a successful read: a bug in a reader or writer. Never caught by
// the harnesses, so libFuzzer reports it (uncaught exception -> abort) and tests fail.
class InvariantViolation : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

[[noreturn]] inline void Violation(const std::string& what) {
  throw InvariantViolation("fuzz invariant violated: " + what);
}
// `what` is built only on failure (hot loops check millions of cells).
inline void CheckInvariant(bool ok, const char* what) {
  if (!ok) Violation(what);
}

// Per-process scratch folder (in /dev/shm when it exists: inputs are rewritten every run),
// removed at exit. BRDFIT_FUZZ_TMP overrides the parent folder.
const std::filesystem::path& ScratchDir();

// Writes bytes to ScratchDir()/name (overwriting) and returns the path.
std::filesystem::path WriteScratch(std::string_view name, const void* data, std::size_t size);

// The bytes of a file ("" if it cannot be read).
std::string ReadAllBytes(const std::filesystem::path& path);

// Writes ScratchDir()/name: a zip archive holding `image` stored (uncompressed) as the member
// merl_nbrdf/m.h5, i.e. NBRDF material "m" (io/nbrdf.h).
std::filesystem::path WriteNbrdfZip(std::string_view name, std::string_view image);

// Number of file descriptors of this process open on files under `dir` (/proc/self/fd), to
// check that a reader closes what it opened, also when it rejects the input. (Counting all
// descriptors would also see the sanitizers' symbolizer pipes.)
std::size_t OpenFdCount(const std::filesystem::path& dir = ScratchDir());

// Consumes bytes from the front of the input (FuzzedDataProvider-like, but available in the
// normal build too). Reading past the end yields zeros.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : p_(data), n_(size) {}
  std::uint8_t U8() { return n_ ? (--n_, *p_++) : 0; }
  std::uint32_t U32() {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= std::uint32_t{U8()} << (8 * k);
    return v;
  }
  // The next min(n, remaining) bytes.
  std::string_view Bytes(std::size_t n) {
    if (n > n_) n = n_;
    std::string_view s(reinterpret_cast<const char*>(p_), n);
    p_ += n;
    n_ -= n;
    return s;
  }
  std::string_view Rest() { return Bytes(n_); }
  std::size_t remaining() const { return n_; }

 private:
  const std::uint8_t* p_;
  std::size_t n_;
};

// The harnesses. Each returns 0 (libFuzzer's convention); findings throw or crash.
int FuzzMerl(const std::uint8_t* data, std::size_t size);
int FuzzHdf5Table(const std::uint8_t* data, std::size_t size);
int FuzzNbrdf(const std::uint8_t* data, std::size_t size);
int FuzzExr(const std::uint8_t* data, std::size_t size);
int FuzzFactorSidecar(const std::uint8_t* data, std::size_t size);
int FuzzScene(const std::uint8_t* data, std::size_t size);
int FuzzFitReport(const std::uint8_t* data, std::size_t size);
int FuzzMesh(const std::uint8_t* data, std::size_t size);
int FuzzFactorFiles(const std::uint8_t* data, std::size_t size);
int FuzzBenchCsv(const std::uint8_t* data, std::size_t size);
int FuzzRenderCache(const std::uint8_t* data, std::size_t size);
int FuzzRglBsdf(const std::uint8_t* data, std::size_t size);

}  // namespace brdfit::fuzz

#ifdef BRDFIT_LIBFUZZER
#define BRDFIT_FUZZ_ENTRY(fn)                                                       \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    return fn(data, size);                                                          \
  }
#else
#define BRDFIT_FUZZ_ENTRY(fn)
#endif
