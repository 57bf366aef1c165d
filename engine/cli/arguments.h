#pragma once
// Minimal command-line parsing shared by the project's commands: "--name value" options,
// "--flag" switches and positional arguments; every malformed value is an invalid_argument
// naming the flag.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pfem::cli {

std::vector<std::string> split(const std::string& s, char sep);

class Arguments {
 public:
  explicit Arguments(std::vector<std::string> args) : args_(std::move(args)) {}
  std::optional<std::string> take_string(const std::string& name);
  std::optional<double> take_double(const std::string& name);
  std::optional<int> take_int(const std::string& name);
  bool take_flag(const std::string& name);
  // Throws unless exactly `positionals` non-option arguments remain.
  void expect_done(std::size_t positionals) const;
  const std::string& positional(std::size_t i) const { return args_.at(i); }

 private:
  std::vector<std::string> args_;
};

}  // namespace pfem::cli
