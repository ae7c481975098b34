// The temporary files of atomic writes (io/atomic_file.h), tracked so that an interrupted run
// removes them (cli/interrupt.h) and a later run removes those a dead process left behind.
// A temporary is named ".<name>.tmp-<pid>-<n>" beside its destination.
#pragma once

#include <chrono>
#include <filesystem>

namespace brdfit {

// The temporary beside `dest` for this process's next write.
std::filesystem::path TemporaryFor(const std::filesystem::path& dest);

// An atomic write of `tmp` starts / has ended (renamed or removed). Once AbandonTemporaries has
// been called, BeginTemporary blocks forever: the process is exiting.
void BeginTemporary(const std::filesystem::path& tmp);
void EndTemporary(const std::filesystem::path& tmp);

// Files that are not temporaries but must go when the run is interrupted (a lock file).
void RemoveOnInterrupt(const std::filesystem::path& p);
void ForgetOnInterrupt(const std::filesystem::path& p);

// For an interrupt: no new write starts; the writes in flight get up to `grace` to finish;
// then every temporary still registered (and every RemoveOnInterrupt file) is removed.
// Returns the number of writes in flight at the call that finished within the grace.
int AbandonTemporaries(std::chrono::milliseconds grace);

// Removes ".<name>.tmp-<pid>-<n>" files beside `dest` whose process no longer exists.
void RemoveStaleTemporaries(const std::filesystem::path& dest);

}  // namespace brdfit
