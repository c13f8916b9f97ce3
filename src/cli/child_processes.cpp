#include "swemps/cli/child_processes.hpp"

#include <sched.h>
#include <spdlog/fmt/fmt.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace swemps::cli {

int usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

Child fork_child(std::size_t task, const std::function<void(int write_fd)>& in_child) {
  int fds[2];
  if (::pipe(fds) != 0) {
    throw std::runtime_error(std::string("cannot make a pipe: ") + std::strerror(errno));
  }
  // Text the parent has buffered would be written again by a child that flushes it.
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot start a child process: fork: ") +
                             std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    in_child(fds[1]);
    ::_exit(127);  // in_child returned, which it must not
  }
  ::close(fds[1]);  // so that the read end sees end-of-file once the child is gone
  Child child;
  child.pid = pid;
  child.task = task;
  child.output_fd = fds[0];
  return child;
}

void run_pool(const std::vector<std::size_t>& order, int jobs, const PoolCalls& calls) {
  std::vector<Child> going;
  std::size_t next = 0;
  bool starting = true;
  while (going.size() > 0 || (starting && next < order.size())) {
    while (starting && going.size() < static_cast<std::size_t>(jobs) && next < order.size()) {
      going.push_back(calls.start(order[next]));
      ++next;
    }
    int status = 0;
    rusage usage{};
    const pid_t pid = ::wait4(-1, &status, WNOHANG, &usage);
    if (pid < 0 && errno != EINTR && errno != ECHILD) {
      throw std::runtime_error(std::string("waiting for a child process: ") + std::strerror(errno));
    }
    const auto child =
        std::find_if(going.begin(), going.end(), [&](const Child& c) { return c.pid == pid; });
    if (pid <= 0 || child == going.end()) {
      starting = calls.between(going) && starting;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      continue;
    }
    const Child ended = *child;
    going.erase(child);
    calls.ended(ended, status, usage, read_all(ended.output_fd));
  }
}

std::string read_all(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return text;
}

void write_all(int fd, const std::string& text) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    written += static_cast<std::size_t>(n);
  }
}

std::string wait_status_text(int status) {
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* name = strsignal(signal);
    return "killed by signal " + std::to_string(signal) + " (" + (name ? name : "unknown") + ")" +
           (signal == SIGKILL ? ", perhaps for want of memory" : "");
  }
  return "exited with status " + std::to_string(WEXITSTATUS(status));
}

ProgramResult run_program(const std::vector<std::string>& argv) {
  ProgramResult result;
  int out[2], err[2];
  if (argv.empty() || ::pipe(out) != 0) return result;
  if (::pipe(err) != 0) {
    ::close(out[0]);
    ::close(out[1]);
    return result;
  }
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(err[1], STDERR_FILENO);
    for (const int fd : {out[0], out[1], err[0], err[1]}) ::close(fd);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    std::fprintf(stderr, "cannot start %s: %s\n", args[0], std::strerror(errno));
    ::_exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  if (pid < 0) {
    ::close(out[0]);
    ::close(err[0]);
    result.err = std::string("fork: ") + std::strerror(errno);
    return result;
  }
  // Small outputs (a job id, a message): reading one stream to its end and then the other
  // cannot fill a pipe and stall.
  result.out = read_all(out[0]);
  result.err = read_all(err[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.status = WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
  return result;
}

std::filesystem::path own_executable() { return std::filesystem::read_symlink("/proc/self/exe"); }

std::string number_text(double v) { return std::isnan(v) ? "nan" : fmt::format("{:.12g}", v); }

std::string text_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t k = 0; k < fields.size(); ++k) line += (k > 0 ? "," : "") + fields[k];
  return line + "\n";
}

}  // namespace swemps::cli
