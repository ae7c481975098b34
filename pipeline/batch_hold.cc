#include "pipeline/batch_hold.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

namespace brdfit::pipeline {

BatchHold BatchHold::FromEnvironment() {
  BatchHold h;
  const char* file = std::getenv("BRDFIT_TEST_HOLD_FILE");
  const char* after = std::getenv("BRDFIT_TEST_HOLD_AFTER_FITS");
  if (!file || !*file || !after || !*after) return h;
  char* end = nullptr;
  const unsigned long long k = std::strtoull(after, &end, 10);
  if (*end != '\0' || after[0] == '-') return h;
  h.file_ = file;
  h.after_fits_ = static_cast<std::size_t>(k);
  return h;
}

void BatchHold::HoldAt(std::size_t fits_done) const {
  if (!after_fits_ || fits_done != *after_fits_) return;
  {
    std::ofstream(file_) << ::getpid() << "\n";
  }
  using namespace std::chrono_literals;
  const auto t0 = std::chrono::steady_clock::now();
  std::error_code ec;
  while (std::filesystem::exists(file_, ec) && std::chrono::steady_clock::now() - t0 < 10min) {
    std::this_thread::sleep_for(5ms);
  }
}

}  // namespace brdfit::pipeline
