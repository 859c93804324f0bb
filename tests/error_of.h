#pragma once
// The message of the std::invalid_argument that `f` throws, or "no exception".
#include <functional>
#include <stdexcept>
#include <string>

namespace sortcell_test {

inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

}  // namespace sortcell_test
