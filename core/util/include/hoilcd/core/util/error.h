// Errors, three kinds kept apart (docs/design.md, "Errors"):
//  - InputError: bad user input (scene file, glTF, dataset, CLI argument); carries where + what.
//  - HOILCD_CHECK*: API misuse by our own callers; throws std::logic_error with file:line.
//  - assert: internal invariants in hot loops (debug only).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace hoilcd {

// One problem found in user input: `where` is "FILE: /json/pointer" or "FILE:LINE" or a flag name.
struct Problem {
  std::string where;
  std::string message;  // what was expected
  std::string ToString() const { return where.empty() ? message : where + ": " + message; }
};

// The one error type for bad user input. Holds every problem found, so a parser can report
// them all at once; what() lists them one per line.
class InputError : public std::runtime_error {
 public:
  InputError(std::string where, std::string message);
  explicit InputError(std::vector<Problem> problems);
  const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::vector<Problem> problems_;
};

// Parsers report through a collector so tests can assert on every message.
class ProblemCollector {
 public:
  void Add(std::string where, std::string message) { problems_.push_back({std::move(where), std::move(message)}); }
  bool empty() const { return problems_.empty(); }
  const std::vector<Problem>& problems() const { return problems_; }
  // Throws InputError with everything collected, if anything was.
  void ThrowIfAny() const;

 private:
  std::vector<Problem> problems_;
};

namespace internal {
[[noreturn]] void ThrowCheck(const char* file, int line, const std::string& message);
}  // namespace internal

}  // namespace hoilcd

#define HOILCD_CHECK(cond)                                                                   \
  do {                                                                                       \
    if (!(cond)) ::hoilcd::internal::ThrowCheck(__FILE__, __LINE__, "Check failed: " #cond); \
  } while (0)

#define HOILCD_CHECK_MSG(cond, msg)                                                   \
  do {                                                                                \
    if (!(cond)) {                                                                    \
      std::ostringstream hoilcd_check_stream_;                                        \
      hoilcd_check_stream_ << "Check failed: " #cond ": " << msg;                     \
      ::hoilcd::internal::ThrowCheck(__FILE__, __LINE__, hoilcd_check_stream_.str()); \
    }                                                                                 \
  } while (0)
