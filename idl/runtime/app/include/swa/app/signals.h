#pragma once
// SIGINT / SIGTERM handling of the SWA programs (program.h does the sequence below): the handler only sets an atomic
// flag; a watcher asks the process role to stop, which leaves through its normal path, so every DDS entity is deleted
// and no /dev/shm segment is left behind.
//
//   installShutdownHandlers();   // first: handlers installed, both signals blocked in this thread
//   Role role(...);              // Fast DDS threads created now inherit the blocked mask
//   acceptShutdownSignals();     // unblock in this (the main) thread only: signals land here, never in a
//   role.run();                  // middleware thread in the middle of a system call

namespace swa::app {

// Installs the handlers and blocks SIGINT / SIGTERM in the calling thread (idempotent). Call before creating any
// DDS entity.
void installShutdownHandlers();

// Unblocks SIGINT / SIGTERM in the calling thread. A signal that arrived while blocked is delivered now.
void acceptShutdownSignals();

// True once SIGINT or SIGTERM arrived.
bool shutdownRequested();

// The signal that requested the shutdown (0 if none).
int shutdownSignal();

// Blocks until SIGINT / SIGTERM arrives or wakeShutdownWatcher() is called (each counts once; one that came before
// the call returns at once). Returns at once if the handlers are not installed. For the one thread that turns the
// flag into a stop (program.h), without polling.
void awaitShutdownOrWake();
void wakeShutdownWatcher();

}  // namespace swa::app
