// A run stopped by SIGINT or SIGTERM (issue 41 part 2): the tool's signal handler only records
// the signal (a lock-free atomic store, async-signal-safe); the long loops check it between rows,
// fragment batches, frames and runs and unwind with Interrupted, so that the output transaction's
// guard removes its temporary folder before the process ends by the signal.
#pragma once

#include <spawn.h>
#include <sys/wait.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" char** environ;

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

// Runs ARGS[0] from the PATH with ARGS and waits for it; true on exit status 0. A stop request
// while it runs (the handlers do not restart waitpid) is passed on to the child, once.
inline bool spawnAndWait(std::vector<std::string> args) {
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid;
    if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return false;
    int status = 0;
    bool passedOn = false;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return false;
        if (const int sig = gInterruptSignal.load(); sig && !passedOn) kill(pid, sig), passedOn = true;
    }
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace pst
