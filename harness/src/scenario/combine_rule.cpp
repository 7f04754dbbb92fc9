// The combine rules of scenario.h: how two bodies' coefficients make the
// pair's value, and each rule's name as scenario files write it.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "talus/harness/scenario/scenario.h"

namespace talus::harness {

double Combine(CombineRule rule, double a, double b) {
  switch (rule) {
    case CombineRule::Sqrt:
      return std::sqrt(a * b);
    case CombineRule::Min:
      return std::min(a, b);
    case CombineRule::Max:
      return std::max(a, b);
    case CombineRule::Multiply:
      return a * b;
    case CombineRule::Average:
      return 0.5 * (a + b);
  }
  assert(false && "unknown combine rule");
  return 0.0;
}

const char* CombineRuleName(CombineRule rule) {
  switch (rule) {
    case CombineRule::Sqrt:
      return "sqrt";
    case CombineRule::Min:
      return "min";
    case CombineRule::Max:
      return "max";
    case CombineRule::Multiply:
      return "multiply";
    case CombineRule::Average:
      return "average";
  }
  assert(false && "unknown combine rule");
  return "";
}

}  // namespace talus::harness
