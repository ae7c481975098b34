// Content keys for the on-disk cache: 64-bit FNV-1a (Fowler, Noll, Vo; IETF draft
// draft-eastlake-fnv, offset basis 14695981039346656037, prime 1099511628211) over the input
// file's bytes and a description of the options. A changed input or option gives a new key;
// a stale cache entry is never read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace brdfit::pipeline {

class Fnv1a64 {
 public:
  void Add(std::string_view bytes) {
    for (unsigned char c : bytes) {
      h_ ^= c;
      h_ *= 1099511628211ULL;
    }
  }
  std::uint64_t value() const { return h_; }
  std::string Hex() const;

 private:
  std::uint64_t h_ = 14695981039346656037ULL;
};

// Hash of a file's content. Throws InputError if it cannot be read.
std::string FileContentKey(const std::filesystem::path& path);

}  // namespace brdfit::pipeline
