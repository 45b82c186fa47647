#include "framework/core/library_error.hpp"

#include <exception>
#include <new>
#include <stdexcept>
#include <string_view>

namespace crowdlab {
namespace {

// Boost.Math reports evaluation and rounding errors as runtime_errors with this head; its domain,
// pole, overflow and underflow errors are the standard library's types.
bool is_boost_math_text(std::string_view what) {
  return what.starts_with("Error in function boost::math");
}

// nlohmann::json (which framework/core does not include) reports type, range and parse errors as
// "[json.exception.<kind>.<id>] <reason>"; the reason is kept, the head is not a user's concern.
constexpr std::string_view kJsonHead = "[json.exception.";

std::string_view json_reason(std::string_view what) {
  const auto end = what.find("] ");
  return end == std::string_view::npos ? what : what.substr(end + 2);
}

// std::stod, std::stoi, ... throw invalid_argument or out_of_range whose what() is their name alone.
bool is_number_conversion_text(std::string_view what) {
  for (std::string_view name : {"stoi", "stol", "stoll", "stoul", "stoull", "stof", "stod", "stold"})
    if (what == name) return true;
  return false;
}

}  // namespace

std::string describe_filesystem_error(const std::filesystem::filesystem_error& e) {
  std::string paths = e.path1().string();
  if (!e.path2().empty()) paths += ", " + e.path2().string();
  // what() is "filesystem error: <operation>: <reason> [path1] [path2]"; the operation sits between the
  // head and the reason, which is the error code's own message.
  std::string_view what = e.what();
  constexpr std::string_view head = "filesystem error: ";
  if (what.starts_with(head)) what.remove_prefix(head.size());
  const std::string reason = e.code().message();
  const auto at = what.find(": " + reason);
  const std::string operation(at == std::string_view::npos ? std::string_view("failed") : what.substr(0, at));
  return (paths.empty() ? std::string("a file") : paths) + ": " + operation + ": " + reason;
}

void rethrow_library_error_as_input(const std::string& input) {
  try {
    throw;
  } catch (const InputError&) {
    throw;
  } catch (const std::filesystem::filesystem_error& e) {
    throw InputError(describe_filesystem_error(e));
  } catch (const std::bad_alloc&) {
    throw InputError(input +
                     ": not enough memory for it (std::bad_alloc); give a smaller input or lower the limits "
                     "that allowed it");
  } catch (const std::domain_error& e) {
    throw InputError(input + ": a statistic could not be computed from it: " + e.what());
  } catch (const std::overflow_error& e) {
    throw InputError(input + ": a statistic could not be computed from it: " + e.what());
  } catch (const std::underflow_error& e) {
    throw InputError(input + ": a statistic could not be computed from it: " + e.what());
  } catch (const std::runtime_error& e) {
    if (is_boost_math_text(e.what()))
      throw InputError(input + ": a statistic could not be computed from it: " + e.what());
    throw;
  } catch (const std::exception& e) {
    const std::string_view what = e.what();
    if (what.starts_with(kJsonHead))
      throw InputError(input +
                       ": a JSON value of the wrong type or shape: " + std::string(json_reason(what)));
    if (is_number_conversion_text(what))
      throw InputError(input + ": a number in it is not a number or out of range (std::" + std::string(what) +
                       ")");
    throw;
  }
}

}  // namespace crowdlab
