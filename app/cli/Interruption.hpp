#pragma once
// Ctrl-C and SIGTERM for the commands. installInterruptHandlers() (runCommandLine calls it) makes
// the first SIGINT/SIGTERM that arrives inside an InterruptibleWork scope only set a flag: the
// frame loops of track, view, simulate and calibrate poll interruptRequested(), stop after the
// frame in hand and finish their outputs up to it; the command then exits with 128 + signal.
// Outside such a scope, or on a second signal, the process removes the temporary files of
// unfinished outputs (TemporaryOutputs) and dies of the signal: an output is complete or absent.
namespace reftrack::app {

void installInterruptHandlers();

// True once SIGINT or SIGTERM arrived in an InterruptibleWork scope.
bool interruptRequested();
// The signal that set it (SIGINT, SIGTERM), or 0.
int interruptSignal();

// While alive, the first signal is deferred to the polling loop. Scopes nest.
class InterruptibleWork {
 public:
  InterruptibleWork();
  ~InterruptibleWork();
  InterruptibleWork(const InterruptibleWork&) = delete;
  InterruptibleWork& operator=(const InterruptibleWork&) = delete;
};

}  // namespace reftrack::app
