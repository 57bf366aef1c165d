#pragma once
// A pfem-server child process listening on 127.0.0.1 (an ephemeral port), started with the
// given flags (--listen is added); its address is read from the line it prints once it
// accepts calls. Its resident memory is read from /proc.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace pfem::testing {

class ServerProcess {
 public:
  explicit ServerProcess(const std::vector<std::string>& flags) {
    int out[2];
    if (::pipe(out) != 0) throw std::runtime_error("pipe");
    const std::string binary = std::string(PFEM_BINARY_DIR) + "/bin/pfem-server";
    std::vector<std::string> args{binary, "--listen", "127.0.0.1:0"};
    args.insert(args.end(), flags.begin(), flags.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], STDOUT_FILENO);
      ::close(out[0]);
      ::close(out[1]);
      ::execv(binary.c_str(), argv.data());
      std::_Exit(127);
    }
    ::close(out[1]);
    FILE* in = ::fdopen(out[0], "r");
    char line[256] = "";
    const bool printed = std::fgets(line, sizeof line, in) != nullptr;
    std::fclose(in);
    if (!printed) throw std::runtime_error("pfem-server printed nothing");
    std::string text(line);
    const auto at = text.rfind(' ');
    address_ = text.substr(at + 1, text.find_last_not_of("\r\n") - at);
  }
  ~ServerProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  const std::string& address() const { return address_; }
  pid_t pid() const { return pid_; }

  // Sends `signal` and waits (at most `seconds`) for the exit; returns the wait status, or -1
  // when it has not exited.
  int stop(int signal, double seconds) {
    ::kill(pid_, signal);
    int status = -1;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return status;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return -1;
  }

  // Resident memory now and its peak since the start (VmRSS, VmHWM), in MB; its threads.
  double rss_mb() const { return status_value("VmRSS:") / 1024.0; }
  double peak_rss_mb() const { return status_value("VmHWM:") / 1024.0; }
  int threads() const { return static_cast<int>(status_value("Threads:")); }

 private:
  double status_value(const std::string& field) const {
    std::ifstream in("/proc/" + std::to_string(pid_) + "/status");
    std::string key;
    double value = 0.0;
    while (in >> key) {
      if (key == field) {
        in >> value;
        return value;
      }
      in.ignore(1 << 20, '\n');
    }
    throw std::runtime_error("no " + field + " for pfem-server " + std::to_string(pid_));
  }

  pid_t pid_ = -1;
  std::string address_;
};

}  // namespace pfem::testing
