// Limit-state expressions: values and precedence, exact gradients against central finite
// differences, and parse errors that name the column.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "clients/reliability/expression.h"

namespace rel = pfem::reliability;
using rel::Expression;

namespace {

const std::vector<std::string> kNames = {"x", "y", "z", "R", "S"};

double eval(const std::string& text, std::vector<double> v = {1.5, -0.5, 2.0, 5.0, 2.0}) {
  return Expression::parse(text, kNames).evaluate(v);
}

std::string error_of(const std::string& text) {
  try {
    Expression::parse(text, kNames);
  } catch (const rel::ExpressionError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ReliabilityExpression, ValuesAndPrecedence) {
  EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7.0);
  EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9.0);
  EXPECT_DOUBLE_EQ(eval("2^3^2"), 512.0);  // right associative
  EXPECT_DOUBLE_EQ(eval("-2^2"), -4.0);    // unary minus binds looser than ^
  EXPECT_DOUBLE_EQ(eval("2^-1"), 0.5);
  EXPECT_DOUBLE_EQ(eval("8 / 4 / 2"), 1.0);  // left associative
  EXPECT_DOUBLE_EQ(eval("1e-3 * 2E+3 + .5"), 2.5);
  EXPECT_DOUBLE_EQ(eval("R - S * (1 + x)"), 5.0 - 2.0 * 2.5);
  EXPECT_DOUBLE_EQ(eval("min(x, y, z) + max(x, y) + abs(y)"), -0.5 + 1.5 + 0.5);
  EXPECT_DOUBLE_EQ(eval("pow(z, 3) - z^3"), 0.0);
  EXPECT_DOUBLE_EQ(eval("ln(exp(x)) - log(exp(x))"), 0.0);
  EXPECT_NEAR(eval("sin(_pi / 2) + cos(0) + log10(1000) + sqrt(16) + _e"), 9.0 + std::numbers::e,
              1e-15);
  EXPECT_DOUBLE_EQ(eval("- - x"), 1.5);
}

TEST(ReliabilityExpression, GradientsMatchFiniteDifferences) {
  const std::vector<std::string> cases = {
      "R - S * (1 + x)",
      "x * y^2 / (1 + z^2) - exp(-x * z)",
      "sqrt(R^2 + S^2) * log(z) - tan(y) + atan(x * y)",
      "pow(z, x) + z^x - abs(y) * sinh(y) + cosh(x) * tanh(z)",
      "min(x, z) * max(R, S * 3) - asin(y) + acos(y / 2) + log2(R) + log10(S)",
      "15.59e4 - R*z^3/(2*S^3) * ((x^2 - 4*y*z*R^2 + x*(z + 4*y)) / (x*y*(x + z + 2*z*R)))",
  };
  const std::vector<double> v = {1.3, -0.4, 2.2, 4.0, 1.7};
  for (const auto& text : cases) {
    SCOPED_TRACE(text);
    const Expression e = Expression::parse(text, kNames);
    std::vector<double> grad(5);
    const double value = e.evaluate(v, grad);
    EXPECT_DOUBLE_EQ(value, e.evaluate(v));
    for (int i = 0; i < 5; ++i) {
      const double h = 1e-6 * std::max(1.0, std::abs(v[i]));
      std::vector<double> vp = v, vm = v;
      vp[i] += h;
      vm[i] -= h;
      const double fd = (e.evaluate(vp) - e.evaluate(vm)) / (2 * h);
      EXPECT_NEAR(grad[i], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "variable " << kNames[i];
    }
  }
}

TEST(ReliabilityExpression, UsedVariables) {
  const Expression e = Expression::parse("S - 2 * x + S * x", kNames);
  EXPECT_EQ(e.used_variables(), (std::vector<int>{0, 4}));
}

TEST(ReliabilityExpression, ParseErrorsNameTheColumn) {
  EXPECT_EQ(error_of("R - S * (1 + U)"), "column 14: unknown variable 'U'");
  EXPECT_EQ(error_of("R - S * (1 + x"), "column 9: '(' is never closed");
  EXPECT_EQ(error_of("R - * S"), "column 5: expected an operand, found '*'");
  EXPECT_EQ(error_of("R S"), "column 3: expected an operator, found 'S'");
  EXPECT_EQ(error_of("R + "), "column 5: expected an operand, found the end of the expression");
  EXPECT_EQ(error_of("R + 1e"), "column 5: malformed number '1e'");
  EXPECT_EQ(error_of("foo(R)"), "column 1: unknown function 'foo'");
  EXPECT_EQ(error_of("pow(R)"), "column 1: function 'pow' takes 2 arguments, got 1");
  EXPECT_EQ(error_of("sqrt(R, S)"), "column 1: function 'sqrt' takes 1 argument, got 2");
  EXPECT_EQ(error_of("R + exp"), "column 5: function 'exp' needs its arguments in parentheses");
  EXPECT_EQ(error_of("R)"), "column 2: unbalanced ')'");
  EXPECT_EQ(error_of("R # S"), "column 3: expected an operator, found '#'");
  EXPECT_EQ(error_of("   "), "column 1: the expression is empty");
}
