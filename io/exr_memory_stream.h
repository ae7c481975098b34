// An OpenEXR output stream into memory. OpenEXR's own file stream does not check the writes
// its destructor flushes (the line-offset table, the last bytes): on a full disk an .exr came
// out empty or cut under its final name with no error. The EXR writers fill this stream and
// hand its bytes to WriteBytesAtomically (io/atomic_file.h), which checks every write(2) and
// the close(2) and renames into place only a complete file.
#pragma once

#include <OpenEXR/ImfIO.h>

#include <algorithm>
#include <cstdint>
#include <string>

namespace brdfit {

class ExrMemoryOStream : public Imf::OStream {
 public:
  explicit ExrMemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}

  void write(const char c[], int n) override {
    const std::size_t end = pos_ + static_cast<std::size_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::copy(c, c + n, bytes_.begin() + static_cast<std::ptrdiff_t>(pos_));
    pos_ = end;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = static_cast<std::size_t>(pos); }

  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
  std::size_t pos_ = 0;
};

}  // namespace brdfit
