// What an InputError says: runs fn and returns the message of the InputError it throws (empty
// when it throws nothing), so a test can assert on the file, pointer or line a message names.
#pragma once

#include <string>

#include "hoilcd/core/util/error.h"

namespace hoilcd::test {

template <typename Fn>
std::string InputErrorOf(Fn fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace hoilcd::test
