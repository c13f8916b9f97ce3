// Settings of the address, leak and undefined-behaviour checks, linked into every sanitized
// program. The checks' runtimes call these functions before main; a variable such as
// ASAN_OPTIONS in the environment still overrides them.

#ifndef SWEMPS_LEAK_SUPPRESSIONS
#error "SWEMPS_LEAK_SUPPRESSIONS must name the leak suppressions file"
#endif

extern "C" {

// Stop at the first error with a full report; also catch use of a stack object after its
// function returned, and static objects that read others before those are constructed.
const char* __asan_default_options() {
  return "halt_on_error=1:detect_stack_use_after_return=1:check_initialization_order=1:"
         "strict_init_order=1:detect_leaks=1";
}

// Leaks inside the libraries the project calls, which it cannot free, are suppressed by name.
const char* __lsan_default_options() { return "suppressions=" SWEMPS_LEAK_SUPPRESSIONS; }

const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }
}
