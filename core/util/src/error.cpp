#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {
std::string Join(const std::vector<Problem>& problems) {
  std::string out;
  for (const Problem& p : problems) {
    if (!out.empty()) out += '\n';
    out += p.ToString();
  }
  return out;
}
}  // namespace

InputError::InputError(std::string where, std::string message)
    : InputError(std::vector<Problem>{{std::move(where), std::move(message)}}) {}

InputError::InputError(std::vector<Problem> problems)
    : std::runtime_error(Join(problems)), problems_(std::move(problems)) {}

void ProblemCollector::ThrowIfAny() const {
  if (!problems_.empty()) throw InputError(problems_);
}

namespace internal {
void ThrowCheck(const char* file, int line, const std::string& message) {
  throw std::logic_error(std::string(file) + ":" + std::to_string(line) + ": " + message);
}
}  // namespace internal
}  // namespace hoilcd
