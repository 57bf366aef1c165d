#include "clients/reliability/expression.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>

namespace pfem::reliability {

namespace {

struct FunctionInfo {
  std::string_view name;
  int arity;  // -1: two or more (min, max); 2: pow
};

bool is_name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

}  // namespace

class Expression::Parser {
 public:
  Parser(std::string_view text, std::span<const std::string> names, std::vector<Node>& nodes)
      : text_(text), names_(names), nodes_(nodes) {}

  void parse() {
    skip_space();
    if (pos_ == text_.size()) fail(1, "the expression is empty");
    parse_expr();
    skip_space();
    if (pos_ != text_.size()) {
      if (text_[pos_] == ')') fail(column(), "unbalanced ')'");
      if (text_[pos_] == ',') fail(column(), "',' outside a function call");
      fail(column(), "expected an operator, found " + describe_here());
    }
  }

 private:
  [[noreturn]] void fail(int col, const std::string& message) { throw ExpressionError(col, message); }
  int column() const { return static_cast<int>(pos_) + 1; }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool at(char c) {
    skip_space();
    return pos_ < text_.size() && text_[pos_] == c;
  }
  std::string describe_here() const {
    if (pos_ >= text_.size()) return "the end of the expression";
    if (is_name_start(text_[pos_])) {
      std::size_t end = pos_;
      while (end < text_.size() && is_name_char(text_[end])) ++end;
      std::string quoted = "'";
      quoted.append(text_.substr(pos_, end - pos_));
      quoted += '\'';
      return quoted;
    }
    std::string quoted = "'";
    quoted += text_[pos_];
    quoted += '\'';
    return quoted;
  }

  int add(Op op, std::vector<int> args) {
    Node n;
    n.op = op;
    n.args = std::move(args);
    nodes_.push_back(std::move(n));
    return static_cast<int>(nodes_.size()) - 1;
  }
  int add_constant(double v) {
    Node n;
    n.op = Op::kConstant;
    n.value = v;
    nodes_.push_back(std::move(n));
    return static_cast<int>(nodes_.size()) - 1;
  }

  int parse_expr() {
    int left = parse_term();
    while (true) {
      if (at('+')) {
        ++pos_;
        left = add(Op::kAdd, {left, parse_term()});
      } else if (at('-')) {
        ++pos_;
        left = add(Op::kSubtract, {left, parse_term()});
      } else {
        return left;
      }
    }
  }

  int parse_term() {
    int left = parse_unary();
    while (true) {
      if (at('*')) {
        ++pos_;
        left = add(Op::kMultiply, {left, parse_unary()});
      } else if (at('/')) {
        ++pos_;
        left = add(Op::kDivide, {left, parse_unary()});
      } else {
        return left;
      }
    }
  }

  int parse_unary() {
    if (at('-')) {
      ++pos_;
      return add(Op::kNegate, {parse_unary()});
    }
    if (at('+')) {
      ++pos_;
      return parse_unary();
    }
    return parse_power();
  }

  int parse_power() {
    const int base = parse_primary();
    if (at('^')) {
      ++pos_;
      return add(Op::kPower, {base, parse_unary()});
    }
    return base;
  }

  int parse_number() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    if (pos_ < text_.size() && text_[pos_] == '.') {
      ++pos_;
      while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    if (pos_ == start + 1 && text_[start] == '.') fail(start + 1, "malformed number '.'");
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t p = pos_ + 1;
      if (p < text_.size() && (text_[p] == '+' || text_[p] == '-')) ++p;
      if (p >= text_.size() || !std::isdigit(static_cast<unsigned char>(text_[p]))) {
        fail(static_cast<int>(start) + 1,
             "malformed number '" + std::string(text_.substr(start, p - start)) + "'");
      }
      while (p < text_.size() && std::isdigit(static_cast<unsigned char>(text_[p]))) ++p;
      pos_ = p;
    }
    const std::string literal(text_.substr(start, pos_ - start));
    return add_constant(std::strtod(literal.c_str(), nullptr));
  }

  int parse_primary() {
    skip_space();
    if (pos_ >= text_.size()) fail(column(), "expected an operand, found the end of the expression");
    const char c = text_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return parse_number();
    if (c == '(') {
      const int open = column();
      ++pos_;
      const int inner = parse_expr();
      if (!at(')')) {
        if (pos_ >= text_.size()) fail(open, "'(' is never closed");
        fail(column(), "expected ')', found " + describe_here());
      }
      ++pos_;
      return inner;
    }
    if (is_name_start(c)) return parse_name();
    fail(column(), "expected an operand, found " + describe_here());
  }

  int parse_name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
    const std::string name(text_.substr(start, pos_ - start));
    const int col = static_cast<int>(start) + 1;
    if (at('(')) return parse_call(name, col);
    for (std::size_t i = 0; i < names_.size(); ++i) {
      if (names_[i] == name) {
        Node n;
        n.op = Op::kVariable;
        n.variable = static_cast<int>(i);
        nodes_.push_back(std::move(n));
        return static_cast<int>(nodes_.size()) - 1;
      }
    }
    if (name == "_pi") return add_constant(std::numbers::pi);
    if (name == "_e") return add_constant(std::numbers::e);
    if (function_op(name)) fail(col, "function '" + name + "' needs its arguments in parentheses");
    fail(col, "unknown variable '" + name + "'");
  }

  static const Op* function_op(const std::string& name) {
    static const std::pair<std::string_view, Op> table[] = {
        {"exp", Op::kExp},   {"log", Op::kLog},     {"ln", Op::kLog},     {"log10", Op::kLog10},
        {"log2", Op::kLog2}, {"sqrt", Op::kSqrt},   {"sin", Op::kSin},    {"cos", Op::kCos},
        {"tan", Op::kTan},   {"asin", Op::kAsin},   {"acos", Op::kAcos},  {"atan", Op::kAtan},
        {"sinh", Op::kSinh}, {"cosh", Op::kCosh},   {"tanh", Op::kTanh},  {"abs", Op::kAbs},
        {"pow", Op::kPower}, {"min", Op::kMin},     {"max", Op::kMax},
    };
    for (const auto& entry : table) {
      if (entry.first == name) return &entry.second;
    }
    return nullptr;
  }

  int parse_call(const std::string& name, int col) {
    const Op* op = function_op(name);
    if (!op) fail(col, "unknown function '" + name + "'");
    ++pos_;  // '('
    std::vector<int> args;
    if (at(')')) fail(column(), "function '" + name + "' needs an argument");
    args.push_back(parse_expr());
    while (at(',')) {
      ++pos_;
      args.push_back(parse_expr());
    }
    if (!at(')')) {
      if (pos_ >= text_.size()) fail(col + static_cast<int>(name.size()), "'(' is never closed");
      fail(column(), "expected ',' or ')', found " + describe_here());
    }
    ++pos_;
    const std::size_t count = args.size();
    if (*op == Op::kPower && count != 2) {
      fail(col, "function 'pow' takes 2 arguments, got " + std::to_string(count));
    } else if ((*op == Op::kMin || *op == Op::kMax) && count < 1) {
      fail(col, "function '" + name + "' takes at least 1 argument");
    } else if (*op != Op::kPower && *op != Op::kMin && *op != Op::kMax && count != 1) {
      fail(col, "function '" + name + "' takes 1 argument, got " + std::to_string(count));
    }
    return add(*op, std::move(args));
  }

  std::string_view text_;
  std::span<const std::string> names_;
  std::vector<Node>& nodes_;
  std::size_t pos_ = 0;
};

Expression Expression::parse(std::string_view text, std::span<const std::string> names) {
  Expression e;
  e.num_variables_ = names.size();
  Parser parser(text, names, e.nodes_);
  parser.parse();
  return e;
}

std::vector<int> Expression::used_variables() const {
  std::vector<int> used;
  for (const auto& n : nodes_) {
    if (n.op == Op::kVariable) used.push_back(n.variable);
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  return used;
}

double Expression::evaluate(std::span<const double> x) const { return evaluate(x, {}); }

double Expression::evaluate(std::span<const double> x, std::span<double> gradient) const {
  if (x.size() != num_variables_) {
    throw std::invalid_argument("Expression::evaluate: expected " + std::to_string(num_variables_) +
                                " values, got " + std::to_string(x.size()));
  }
  const std::size_t n = nodes_.size();
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Node& node = nodes_[i];
    const auto arg = [&](int k) { return v[node.args[k]]; };
    switch (node.op) {
      case Op::kConstant: v[i] = node.value; break;
      case Op::kVariable: v[i] = x[node.variable]; break;
      case Op::kAdd: v[i] = arg(0) + arg(1); break;
      case Op::kSubtract: v[i] = arg(0) - arg(1); break;
      case Op::kMultiply: v[i] = arg(0) * arg(1); break;
      case Op::kDivide: v[i] = arg(0) / arg(1); break;
      case Op::kPower: v[i] = std::pow(arg(0), arg(1)); break;
      case Op::kNegate: v[i] = -arg(0); break;
      case Op::kExp: v[i] = std::exp(arg(0)); break;
      case Op::kLog: v[i] = std::log(arg(0)); break;
      case Op::kLog10: v[i] = std::log10(arg(0)); break;
      case Op::kLog2: v[i] = std::log2(arg(0)); break;
      case Op::kSqrt: v[i] = std::sqrt(arg(0)); break;
      case Op::kSin: v[i] = std::sin(arg(0)); break;
      case Op::kCos: v[i] = std::cos(arg(0)); break;
      case Op::kTan: v[i] = std::tan(arg(0)); break;
      case Op::kAsin: v[i] = std::asin(arg(0)); break;
      case Op::kAcos: v[i] = std::acos(arg(0)); break;
      case Op::kAtan: v[i] = std::atan(arg(0)); break;
      case Op::kSinh: v[i] = std::sinh(arg(0)); break;
      case Op::kCosh: v[i] = std::cosh(arg(0)); break;
      case Op::kTanh: v[i] = std::tanh(arg(0)); break;
      case Op::kAbs: v[i] = std::abs(arg(0)); break;
      case Op::kMin:
      case Op::kMax: {
        double best = arg(0);
        for (std::size_t k = 1; k < node.args.size(); ++k) {
          const double c = arg(static_cast<int>(k));
          if (node.op == Op::kMin ? c < best : c > best) best = c;
        }
        v[i] = best;
        break;
      }
    }
  }
  const double value = v[n - 1];
  if (gradient.empty()) return value;
  if (gradient.size() != num_variables_) {
    throw std::invalid_argument("Expression::evaluate: gradient has the wrong size");
  }
  std::fill(gradient.begin(), gradient.end(), 0.0);
  std::vector<double> adj(n, 0.0);
  adj[n - 1] = 1.0;
  for (std::size_t ii = n; ii-- > 0;) {
    const double a = adj[ii];
    if (a == 0.0) continue;
    const Node& node = nodes_[ii];
    const auto arg = [&](int k) { return v[node.args[k]]; };
    const auto push = [&](int k, double d) { adj[node.args[k]] += a * d; };
    switch (node.op) {
      case Op::kConstant: break;
      case Op::kVariable: gradient[node.variable] += a; break;
      case Op::kAdd: push(0, 1.0); push(1, 1.0); break;
      case Op::kSubtract: push(0, 1.0); push(1, -1.0); break;
      case Op::kMultiply: push(0, arg(1)); push(1, arg(0)); break;
      case Op::kDivide: push(0, 1.0 / arg(1)); push(1, -arg(0) / (arg(1) * arg(1))); break;
      case Op::kPower: {
        const double b = arg(0);
        const double e = arg(1);
        push(0, e == 0.0 ? 0.0 : e * std::pow(b, e - 1.0));
        // d/de only where the exponent is not a constant (b^e ln b is undefined for b < 0).
        if (nodes_[node.args[1]].op != Op::kConstant) {
          push(1, b > 0 ? v[ii] * std::log(b) : (b == 0.0 ? 0.0 : std::nan("")));
        }
        break;
      }
      case Op::kNegate: push(0, -1.0); break;
      case Op::kExp: push(0, v[ii]); break;
      case Op::kLog: push(0, 1.0 / arg(0)); break;
      case Op::kLog10: push(0, 1.0 / (arg(0) * std::numbers::ln10)); break;
      case Op::kLog2: push(0, 1.0 / (arg(0) * std::numbers::ln2)); break;
      case Op::kSqrt: push(0, 0.5 / v[ii]); break;
      case Op::kSin: push(0, std::cos(arg(0))); break;
      case Op::kCos: push(0, -std::sin(arg(0))); break;
      case Op::kTan: push(0, 1.0 + v[ii] * v[ii]); break;
      case Op::kAsin: push(0, 1.0 / std::sqrt(1.0 - arg(0) * arg(0))); break;
      case Op::kAcos: push(0, -1.0 / std::sqrt(1.0 - arg(0) * arg(0))); break;
      case Op::kAtan: push(0, 1.0 / (1.0 + arg(0) * arg(0))); break;
      case Op::kSinh: push(0, std::cosh(arg(0))); break;
      case Op::kCosh: push(0, std::sinh(arg(0))); break;
      case Op::kTanh: push(0, 1.0 - v[ii] * v[ii]); break;
      case Op::kAbs: push(0, arg(0) > 0 ? 1.0 : (arg(0) < 0 ? -1.0 : 0.0)); break;
      case Op::kMin:
      case Op::kMax: {
        for (std::size_t k = 0; k < node.args.size(); ++k) {
          if (arg(static_cast<int>(k)) == v[ii]) {
            push(static_cast<int>(k), 1.0);
            break;
          }
        }
        break;
      }
    }
  }
  return value;
}

}  // namespace pfem::reliability
