#pragma once
// Limit-state expressions in muparser's syntax, parsed by recursive descent into an
// expression tree that is evaluated with its exact gradient by reverse-mode automatic
// differentiation over the tree (one forward sweep for the values, one backward sweep for
// the adjoints).
//
// Grammar (precedence from low to high):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?          right associative: 2^3^2 = 2^9, -2^2 = -4
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
// Numbers: 12, 1.5, .5, 1e-3, 2.5E+4. Constants: _pi, _e. Functions: exp, log and ln
// (natural), log10, log2, sqrt, sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, abs,
// pow(x, y), min(a, b, ...), max(a, b, ...). Derivatives at kinks: abs'(0) = 0; min/max
// follow the first argument that attains the extreme.
//
// An Expression is immutable after parsing; evaluate() may be called from several threads.
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pfem::reliability {

// A parse error at a 1-based column of the expression text.
class ExpressionError : public std::runtime_error {
 public:
  ExpressionError(int column, const std::string& message)
      : std::runtime_error("column " + std::to_string(column) + ": " + message),
        column_(column),
        message_(message) {}
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  int column_;
  std::string message_;
};

class Expression {
 public:
  // Parses `text` over the variables `names` (x[i] is names[i]). Throws ExpressionError for
  // a syntax error, an unknown name or function, or a wrong number of arguments.
  static Expression parse(std::string_view text, std::span<const std::string> names);

  std::size_t num_variables() const { return num_variables_; }
  // Indices of the variables the expression uses, ascending.
  std::vector<int> used_variables() const;

  // The value at x (x.size() == num_variables()).
  double evaluate(std::span<const double> x) const;
  // The value, and the exact gradient into `gradient` when it is non-empty (its size must be
  // num_variables()).
  double evaluate(std::span<const double> x, std::span<double> gradient) const;

 private:
  enum class Op {
    kConstant, kVariable, kAdd, kSubtract, kMultiply, kDivide, kPower, kNegate,
    kExp, kLog, kLog10, kLog2, kSqrt, kSin, kCos, kTan, kAsin, kAcos, kAtan,
    kSinh, kCosh, kTanh, kAbs, kMin, kMax,
  };
  struct Node {
    Op op = Op::kConstant;
    double value = 0.0;        // kConstant
    int variable = -1;         // kVariable
    std::vector<int> args;     // children, always earlier in nodes_
  };
  class Parser;

  Expression() = default;
  std::vector<Node> nodes_;  // topological order: children before parents; root is last
  std::size_t num_variables_ = 0;
};

}  // namespace pfem::reliability
