#pragma once
// SIGINT and SIGTERM ask a run to stop well: the handler only records which signal came; the
// time loop looks after every step, then writes the state it reached, closes its files and
// exits with its own status. The first signal restores the default action, so that a second
// one ends the process at once (for a run that is stuck, or a user who will not wait).

namespace swemps::cli {

// Installs the handlers while it lives and restores the previous actions when it goes. One at
// a time.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  int received() const;  // the signal that asked to stop; 0 while none has
};

// "SIGINT", "SIGTERM", or "a signal".
const char* signal_name(int signal_number);

}  // namespace swemps::cli
