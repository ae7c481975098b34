#include "io/temp_files.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <mutex>
#include <set>
#include <string>

namespace brdfit {

namespace fs = std::filesystem;

namespace {

struct Registry {
  std::mutex mu;
  std::condition_variable cv;
  std::multiset<std::string> in_flight;  // temporaries being written
  std::set<std::string> on_interrupt;    // other files to remove
  bool abandoned = false;
};

Registry& Reg() {
  static Registry* r = new Registry;  // never destroyed: usable until _exit
  return *r;
}

std::string Prefix(const fs::path& dest) {
  std::string s = dest.filename().string();  // (built in place: GCC 12's -Wrestrict on "." + s)
  s.insert(0, 1, '.');
  return s + ".tmp-";
}

}  // namespace

fs::path TemporaryFor(const fs::path& dest) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = dest.has_parent_path() ? dest.parent_path() : fs::path(".");
  return dir / (Prefix(dest) + std::to_string(::getpid()) + "-" + std::to_string(counter++));
}

void BeginTemporary(const fs::path& tmp) {
  Registry& r = Reg();
  std::unique_lock<std::mutex> lock(r.mu);
  r.cv.wait(lock, [&] { return !r.abandoned; });
  r.in_flight.insert(tmp.string());
}

void EndTemporary(const fs::path& tmp) {
  Registry& r = Reg();
  std::lock_guard<std::mutex> lock(r.mu);
  if (auto it = r.in_flight.find(tmp.string()); it != r.in_flight.end()) r.in_flight.erase(it);
  r.cv.notify_all();
}

void RemoveOnInterrupt(const fs::path& p) {
  std::lock_guard<std::mutex> lock(Reg().mu);
  Reg().on_interrupt.insert(p.string());
}

void ForgetOnInterrupt(const fs::path& p) {
  std::lock_guard<std::mutex> lock(Reg().mu);
  Reg().on_interrupt.erase(p.string());
}

int AbandonTemporaries(std::chrono::milliseconds grace) {
  Registry& r = Reg();
  std::unique_lock<std::mutex> lock(r.mu);
  r.abandoned = true;
  const std::size_t at_call = r.in_flight.size();
  r.cv.wait_for(lock, grace, [&] { return r.in_flight.empty(); });
  const int drained = static_cast<int>(at_call - r.in_flight.size());
  for (const std::string& p : r.in_flight) ::unlink(p.c_str());
  for (const std::string& p : r.on_interrupt) ::unlink(p.c_str());
  return drained;
}

void RemoveStaleTemporaries(const fs::path& dest) {
  const fs::path dir = dest.has_parent_path() ? dest.parent_path() : fs::path(".");
  const std::string prefix = Prefix(dest);
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.starts_with(prefix)) continue;
    const std::string rest = name.substr(prefix.size());  // "<pid>-<n>"
    const auto dash = rest.find('-');
    if (dash == std::string::npos || dash == 0 || dash > 9) continue;
    if (rest.find_first_not_of("0123456789-") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dash)));
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(pid, 0) == -1 && errno == ESRCH) {
      std::error_code rm;
      fs::remove(it->path(), rm);
    }
  }
}

}  // namespace brdfit
