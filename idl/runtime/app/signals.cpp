#include "swa/app/signals.h"

#include <pthread.h>
#include <semaphore.h>

#include <atomic>
#include <cerrno>
#include <csignal>

namespace swa::app {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");
// Posted by the handler (sem_post is async-signal-safe) and by wakeShutdownWatcher(): a watcher waits on it instead of
// polling the flag (a 10 ms poll woke every SWA process 100 times a second for nothing).
sem_t g_wake;
std::atomic<bool> g_wake_ready{false};

extern "C" void onShutdownSignal(int sig) {
  g_signal.store(sig);
  if (g_wake_ready.load()) sem_post(&g_wake);
}

sigset_t shutdownSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

}  // namespace

void installShutdownHandlers() {
  if (!g_wake_ready.exchange(true)) sem_init(&g_wake, 0, 0);
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

void awaitShutdownOrWake() {
  if (!g_wake_ready.load()) return;
  // EINTR: a signal's handler ran in this thread; it also posted, so waiting again returns at once.
  while (sem_wait(&g_wake) != 0 && errno == EINTR) {
  }
}

void wakeShutdownWatcher() {
  if (g_wake_ready.load()) sem_post(&g_wake);
}

int shutdownSignal() { return g_signal.load(); }

}  // namespace swa::app
