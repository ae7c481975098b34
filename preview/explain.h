// What a render loaded, computed, reused and skipped (`brdfit render --explain`).
#pragma once

#include <string>
#include <vector>

namespace brdfit::preview {

class ExplainLog {
 public:
  // category: "load", "compute", "reuse", "skip", "shader", "draw", "note".
  void Add(std::string category, std::string message) {
    entries_.push_back({std::move(category), std::move(message)});
  }
  struct Entry {
    std::string category, message;
  };
  const std::vector<Entry>& entries() const { return entries_; }
  std::string Format() const {
    std::string s;
    for (const auto& e : entries_) s += "explain: " + e.category + ": " + e.message + "\n";
    return s;
  }

 private:
  std::vector<Entry> entries_;
};

}  // namespace brdfit::preview
