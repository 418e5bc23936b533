// What a fuzz target accepts from a reader: a result, or InputError (bad input, named). Any other
// exception, like a crash, a sanitizer report, a leak or a timeout, is a finding.
#pragma once

#include "core/errors.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <typeinfo>

namespace tissuemesh::fuzz {

/// Runs `read()`; returns normally on success or InputError, aborts (a libFuzzer crash, with the
/// exception's type and text on stderr) on any other exception.
template <typename Read>
void expect_result_or_input_error(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz finding: %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  }
}

}  // namespace tissuemesh::fuzz
