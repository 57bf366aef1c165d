#include "engine/cli/arguments.h"

#include <charconv>
#include <type_traits>

namespace pfem::cli {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string item;
  for (char c : s) {
    if (c == sep) {
      if (!item.empty()) out.push_back(item);
      item.clear();
    } else {
      item += c;
    }
  }
  if (!item.empty()) out.push_back(item);
  return out;
}

std::optional<std::string> Arguments::take_string(const std::string& name) {
  for (std::size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] != name) continue;
    if (i + 1 >= args_.size()) throw std::invalid_argument(name + " needs a value");
    std::string value = args_[i + 1];
    args_.erase(args_.begin() + i, args_.begin() + i + 2);
    taken_.insert(name);
    return value;
  }
  return std::nullopt;
}

std::optional<double> Arguments::take_double(const std::string& name) {
  auto s = take_string(name);
  if (!s) return std::nullopt;
  try {
    std::size_t used = 0;
    const double v = std::stod(*s, &used);
    if (used != s->size()) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw std::invalid_argument(name + ": '" + *s + "' is not a number");
  }
}

template <class T>
std::optional<T> Arguments::take_integer(const std::string& name) {
  auto s = take_string(name);
  if (!s) return std::nullopt;
  T v{};
  const char* end = s->data() + s->size();
  const auto [stop, error] = std::from_chars(s->data(), end, v);
  if (error == std::errc() && stop == end) return v;
  throw std::invalid_argument(name + ": '" + *s + "' is not " +
                              (std::is_signed_v<T> ? "an integer" : "a non-negative integer"));
}

std::optional<int> Arguments::take_int(const std::string& name) { return take_integer<int>(name); }

std::optional<std::int64_t> Arguments::take_int64(const std::string& name) {
  return take_integer<std::int64_t>(name);
}

std::optional<std::uint64_t> Arguments::take_uint64(const std::string& name) {
  return take_integer<std::uint64_t>(name);
}

bool Arguments::take_flag(const std::string& name) {
  for (std::size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] == name) {
      args_.erase(args_.begin() + i);
      taken_.insert(name);
      return true;
    }
  }
  return false;
}

void Arguments::expect_done(std::size_t positionals) const {
  for (const auto& a : args_) {
    if (taken_.count(a)) throw std::invalid_argument(a + " given more than once");
    if (a.size() > 1 && a[0] == '-') throw std::invalid_argument("unknown option " + a);
  }
  if (args_.size() != positionals) {
    std::string message = "expected " + std::to_string(positionals) + " file argument(s), got " +
                          std::to_string(args_.size());
    for (std::size_t i = 0; i < args_.size(); ++i) message += (i ? " '" : ": '") + args_[i] + "'";
    throw std::invalid_argument(message);
  }
}

}  // namespace pfem::cli
