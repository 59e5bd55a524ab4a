#include "app/cli/Interruption.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <csignal>

#include "engine/core/TemporaryOutputs.hpp"

namespace reftrack::app {

namespace {

std::atomic<int> pendingSignal{0};
std::atomic<int> workScopes{0};
static_assert(std::atomic<int>::is_always_lock_free, "used from a signal handler");

void dieOf(int signal) {
  removeTemporaryOutputs();
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  sigemptyset(&fallback.sa_mask);
  sigaction(signal, &fallback, nullptr);
  raise(signal);  // delivered on return from this handler: the default action ends the process
}

extern "C" void onInterrupt(int signal) {
  if (workScopes.load() > 0) {
    int none = 0;
    if (pendingSignal.compare_exchange_strong(none, signal)) {
      static const char message[] =
          "\nreftrack: interrupted; finishing the outputs up to the current frame "
          "(interrupt again to abandon them)\n";
      [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, message, sizeof message - 1);
      return;
    }
  }
  dieOf(signal);
}

}  // namespace

void installInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool interruptRequested() { return pendingSignal.load() != 0; }

int interruptSignal() { return pendingSignal.load(); }

InterruptibleWork::InterruptibleWork() { workScopes.fetch_add(1); }

InterruptibleWork::~InterruptibleWork() { workScopes.fetch_sub(1); }

}  // namespace reftrack::app
