// SIGINT, SIGTERM and SIGHUP (docs/reliability.md, "Signals"): main() blocks them in every
// thread and one thread waits for them. On a signal no new atomic write starts, the writes in
// flight get a moment to finish, every temporary (and lock file) is removed, the running
// command's hook prints what was kept, and the process exits with 128 + the signal number
// (130, 143, 129).
#pragma once

#include <functional>

namespace brdfit::cli {

// Call first thing in main(), before any thread exists.
void InstallInterruptHandler();

// What the running command does on an interrupt, after the temporaries are gone (runs on the
// signal thread; e.g. close the progress line, print "interrupted: N fits kept, rerun to
// resume"). `drained`: writes that were in flight when the signal came and finished since.
// Without a hook, "brdfit: interrupted" is printed.
using InterruptHook = std::function<void(int signal, int drained)>;
void SetInterruptHook(InterruptHook hook);

}  // namespace brdfit::cli
