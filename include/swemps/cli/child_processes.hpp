#pragma once
// What the commands that run other runs in child processes share (study, ensemble): the cores
// this process may use, pipes read and written whole, and what a wait status says.

#include <sys/resource.h>
#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace swemps::cli {

// One task of a pool, running in a child process that writes what it has to say (a result, or
// its messages) into a pipe, read whole when it ends. What a child writes must fit the pipe's
// buffer (64 KiB on Linux), since the pipe is read only once the child has ended.
struct Child {
  pid_t pid = -1;
  std::size_t task = 0;
  int output_fd = -1;  // the read end of the child's pipe
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  bool stopped = false;  // killed by the parent (a time limit)
};

// Forks a child for `task`: `in_child(write_fd)` runs in it and must not return (it execs, or
// leaves through _exit). Throws std::runtime_error when the pipe or the fork fails.
Child fork_child(std::size_t task, const std::function<void(int write_fd)>& in_child);

// What a pool is told and asked while its children run.
struct PoolCalls {
  std::function<Child(std::size_t task)> start;  // forks the task's child (fork_child)
  // Between polls that saw no child end (about ten a second), with the children going: tick a
  // progress bar, stop overdue children, pass a signal on. Returns false once no more tasks
  // should start; the pool then waits for those going.
  std::function<bool(std::vector<Child>& going)> between;
  // A child has ended: its wait status, its resource use and what it wrote to its pipe.
  std::function<void(const Child& child, int wait_status, const rusage& usage,
                     const std::string& output)>
      ended;
};

// Runs the tasks in `order` in child processes, `jobs` at once, until all have ended (or
// between() said to start no more and those going have ended).
void run_pool(const std::vector<std::size_t>& order, int jobs, const PoolCalls& calls);

// The cores this process may run on (its affinity mask, which a container, taskset or a
// scheduler's allocation may narrow), without touching OpenMP.
int usable_cores();

// Everything until end of file (the fd is closed), and all of `text` written (a write to a
// reader that is gone is given up silently: nobody is left to tell).
std::string read_all(int fd);
void write_all(int fd, const std::string& text);

// What the wait status of a child that sent no result says: "killed by signal 9 (Killed),
// perhaps for want of memory", "exited with status 1".
std::string wait_status_text(int status);

// Runs a program (found on PATH when `argv[0]` has no '/') to its end and returns its exit
// status (128 + n when signal n ended it; 127 when it could not be started) and what it
// printed on each stream.
struct ProgramResult {
  int status = 127;
  std::string out, err;
};
ProgramResult run_program(const std::vector<std::string>& argv);

// This program's own executable, to start as a child (/proc/self/exe resolved).
std::filesystem::path own_executable();

// CSV fields: a number with 12 significant digits ("nan" when unknown), and text quoted when
// it holds a comma, a quote or a line break.
std::string number_text(double v);
std::string text_field(const std::string& text);
std::string csv_line(const std::vector<std::string>& fields);

}  // namespace swemps::cli
