#pragma once
// SIGINT / SIGTERM handling for the DDS nodes: the handler only sets an atomic flag; the node's loop polls it and
// leaves through the normal path, so every DDS entity is deleted and no /dev/shm segment is left behind.
//
//   installShutdownHandlers();   // first thing in main(): handlers installed, both signals blocked in this thread
//   Node node(...);              // Fast DDS threads created now inherit the blocked mask
//   acceptShutdownSignals();     // unblock in this (the worker) thread only: signals land here, never in a
//   node.run();                  // middleware thread in the middle of a system call

namespace swa::dds {

// Installs the handlers and blocks SIGINT / SIGTERM in the calling thread (idempotent). Call before creating any
// DDS entity.
void installShutdownHandlers();

// Unblocks SIGINT / SIGTERM in the calling thread. A signal that arrived while blocked is delivered now.
void acceptShutdownSignals();

// True once SIGINT or SIGTERM arrived.
bool shutdownRequested();

// The signal that requested the shutdown (0 if none).
int shutdownSignal();

}  // namespace swa::dds
