#include "engine/cli/arguments.h"

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

std::optional<int> Arguments::take_int(const std::string& name) {
  auto s = take_string(name);
  if (!s) return std::nullopt;
  try {
    std::size_t used = 0;
    const int v = std::stoi(*s, &used);
    if (used != s->size()) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw std::invalid_argument(name + ": '" + *s + "' is not an integer");
  }
}

bool Arguments::take_flag(const std::string& name) {
  for (std::size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] == name) {
      args_.erase(args_.begin() + i);
      return true;
    }
  }
  return false;
}

void Arguments::expect_done(std::size_t positionals) const {
  for (const auto& a : args_)
    if (a.size() > 2 && a.rfind("--", 0) == 0) throw std::invalid_argument("unknown option " + a);
  if (args_.size() != positionals)
    throw std::invalid_argument("expected " + std::to_string(positionals) + " file argument(s)");
}

}  // namespace pfem::cli
