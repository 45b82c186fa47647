#pragma once
// Library exceptions at the input boundary (issue 33 item 4). The standard library and Boost.Math throw
// their own exceptions, whose what() names neither the input nor the place ("filesystem error: cannot
// create directories: Not a directory [out/x]", "Error in function boost::math::...: Overflow Error",
// "std::bad_alloc"); the CLI printed them raw with exit 1. Where a command knows the file it is
// reading or writing, it runs that work inside at_input_boundary, which turns them into an InputError
// (exit 2) that names the file; main() applies the same rewrite to whatever still escapes.
//   std::filesystem::filesystem_error   -> "<path>[, <path2>]: <operation>: <reason>"
//   Boost.Math errors (std::domain_error, std::overflow_error, std::underflow_error, and the
//   runtime_errors whose text starts "Error in function boost::math")
//                                        -> "<input>: a statistic could not be computed from it: ..."
//   std::bad_alloc                       -> "<input>: not enough memory for it; ..."
//   nlohmann::json's exceptions ("[json.exception.type_error.302] type must be string, but is number")
//                                        -> "<input>: a JSON value of the wrong type or shape: type must ..."
//   std::stod and its kin (invalid_argument / out_of_range whose what() is the function's name alone)
//                                        -> "<input>: a number in it is not a number or out of range (stod)"
// Every other exception, InputError included, passes unchanged.
#include <filesystem>
#include <optional>
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab {

/// "path1[, path2]: operation: reason" (what() without its "filesystem error: " head and path tail).
std::string describe_filesystem_error(const std::filesystem::filesystem_error& e);

/// Call inside a catch block: throws the InputError for the exception being handled when it is one of
/// the library errors above (naming `input`), else rethrows it unchanged.
[[noreturn]] void rethrow_library_error_as_input(const std::string& input);

/// Runs `work`, turning the library errors above into InputErrors that name `input`.
template <class Work>
decltype(auto) at_input_boundary(const std::string& input, Work&& work) {
  try {
    return work();
  } catch (...) {
    rethrow_library_error_as_input(input);
  }
}

}  // namespace crowdlab
