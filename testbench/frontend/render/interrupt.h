// A run stopped by SIGINT or SIGTERM (issue 41 part 2): the tool's signal handler only records
// the signal (a lock-free atomic store, async-signal-safe); the long loops check it between rows,
// fragment batches, frames and runs and unwind with Interrupted, so that the output transaction's
// guard removes its temporary folder before the process ends by the signal.
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>

namespace pst {

// The signal that asked the run to stop (0: none). Set only by the tool's handler.
inline std::atomic<int> gInterruptSignal{0};

struct Interrupted : std::runtime_error {
    explicit Interrupted(int sig) : std::runtime_error("interrupted by signal " + std::to_string(sig)), signal(sig) {}
    int signal;
};

inline bool interrupted() { return gInterruptSignal.load(std::memory_order_relaxed) != 0; }

inline void throwIfInterrupted() {
    if (const int s = gInterruptSignal.load(std::memory_order_relaxed)) throw Interrupted(s);
}

}  // namespace pst
