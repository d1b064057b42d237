#include "swa/app/signals.h"

#include <pthread.h>

#include <atomic>
#include <csignal>

namespace swa::app {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void onShutdownSignal(int sig) { g_signal.store(sig); }

sigset_t shutdownSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

}  // namespace

void installShutdownHandlers() {
  struct sigaction action {};
  action.sa_handler = onShutdownSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  const sigset_t set = shutdownSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

void acceptShutdownSignals() {
  const sigset_t set = shutdownSignals();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

bool shutdownRequested() { return g_signal.load() != 0; }

int shutdownSignal() { return g_signal.load(); }

}  // namespace swa::app
