#include "swemps/cli/stop_signals.hpp"

#include <signal.h>

#include <csignal>
#include <stdexcept>

namespace swemps::cli {

namespace {

// All a handler may touch: a lock-free flag of a type signals may write.
volatile std::sig_atomic_t stop_signal = 0;
bool installed = false;
struct sigaction previous_int, previous_term;

extern "C" void record_stop_signal(int signal_number) { stop_signal = signal_number; }

}  // namespace

StopSignals::StopSignals() {
  if (installed) throw std::logic_error("StopSignals: already installed");
  stop_signal = 0;
  struct sigaction action {};
  action.sa_handler = record_stop_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: the default action is back once the handler has run, so a second signal
  // ends the process. SA_RESTART: writes the signal interrupts go on rather than fail.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
  installed = true;
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
  installed = false;
}

int StopSignals::received() const { return stop_signal; }

const char* signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "a signal";
  }
}

}  // namespace swemps::cli
