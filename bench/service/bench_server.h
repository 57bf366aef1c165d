#pragma once
// The server a service bench talks to: the one at --server, or else one started in this process
// on 127.0.0.1 with its store in a temporary folder, removed when the bench ends.
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "server/server.h"

namespace pfem::bench {

class BenchServer {
 public:
  // options: the in-process server's (listen and data_dir are set here); name: the folder's.
  BenchServer(std::optional<std::string> external, const std::string& name, pfem::server::ServerOptions options) {
    if (external) {
      address_ = std::move(*external);
      return;
    }
    data_dir_ = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
    options.listen = "127.0.0.1:0";
    options.data_dir = data_dir_;
    server_ = std::make_unique<pfem::server::Server>(options);
    address_ = server_->address();
  }
  ~BenchServer() {
    server_.reset();
    if (!data_dir_.empty()) std::filesystem::remove_all(data_dir_);
  }
  BenchServer(const BenchServer&) = delete;
  BenchServer& operator=(const BenchServer&) = delete;

  const std::string& address() const { return address_; }
  bool in_process() const { return server_ != nullptr; }

 private:
  std::unique_ptr<pfem::server::Server> server_;
  std::filesystem::path data_dir_;
  std::string address_;
};

}  // namespace pfem::bench
