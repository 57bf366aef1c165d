#pragma once
// Minimal command-line parsing shared by the project's commands: "--name value" options,
// "--flag" switches and positional arguments; every malformed value is an invalid_argument
// naming the flag.
#include <cstdint>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace pfem::cli {

std::vector<std::string> split(const std::string& s, char sep);

class Arguments {
 public:
  explicit Arguments(std::vector<std::string> args) : args_(std::move(args)) {}
  // Each take_ removes the first "name [value]" it finds; call again for a repeatable option.
  std::optional<std::string> take_string(const std::string& name);
  std::optional<double> take_double(const std::string& name);
  std::optional<int> take_int(const std::string& name);
  std::optional<std::int64_t> take_int64(const std::string& name);
  std::optional<std::uint64_t> take_uint64(const std::string& name);  // no sign allowed
  bool take_flag(const std::string& name);
  // Throws unless exactly `positionals` non-option arguments remain: an option left over is
  // unknown ("-x", "--xyz"), or given more than once if it was taken before.
  void expect_done(std::size_t positionals) const;
  const std::string& positional(std::size_t i) const { return args_.at(i); }
  std::size_t remaining() const { return args_.size(); }  // arguments not taken yet

 private:
  template <class T>
  std::optional<T> take_integer(const std::string& name);

  std::vector<std::string> args_;
  std::set<std::string> taken_;  // names of the options taken so far
};

}  // namespace pfem::cli
