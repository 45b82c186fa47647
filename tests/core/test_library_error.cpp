// Library exceptions become InputErrors that name the input (framework/core/library_error.hpp, issue 33
// item 4): the standard library's filesystem errors, Boost.Math's errors and bad_alloc, raw before.
#include <catch2/catch.hpp>
#include <filesystem>
#include <functional>
#include <new>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <system_error>

#include "framework/core/error.hpp"
#include "framework/core/library_error.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_library_error {

using namespace crowdlab;

namespace {

std::string input_error_of(const std::function<void()>& work) {
  try {
    at_input_boundary("answers.csv", work);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST_CASE("core: a filesystem error names its paths, the operation and the reason") {
  const std::filesystem::filesystem_error e("cannot create directories", "out/x",
                                            std::make_error_code(std::errc::not_a_directory));
  CHECK(describe_filesystem_error(e) == "out/x: cannot create directories: Not a directory");
  const std::filesystem::filesystem_error two("cannot copy", "a", "b",
                                              std::make_error_code(std::errc::permission_denied));
  CHECK(describe_filesystem_error(two) == "a, b: cannot copy: Permission denied");
  CHECK(input_error_of([&] { throw e; }) == "out/x: cannot create directories: Not a directory");
}

TEST_CASE("core: Boost.Math errors and bad_alloc name the input, other exceptions pass unchanged") {
  CHECK(input_error_of([] { throw std::domain_error("Error in function boost::math::cdf: Scale is nan"); }) ==
        "answers.csv: a statistic could not be computed from it: Error in function boost::math::cdf: "
        "Scale is nan");
  CHECK_THAT(input_error_of([] { throw std::overflow_error("Overflow Error"); }),
             Catch::StartsWith("answers.csv: a statistic"));
  // boost::math::evaluation_error is a runtime_error with Boost.Math's head.
  CHECK_THAT(input_error_of([] { throw std::runtime_error("Error in function boost::math::x: Evaluation"); }),
             Catch::StartsWith("answers.csv: a statistic"));
  CHECK_THAT(input_error_of([] { throw std::bad_alloc(); }),
             Catch::StartsWith("answers.csv: not enough memory for it"));
  CHECK(input_error_of([] { throw InputError("x.csv:3: bad"); }) == "x.csv:3: bad");
  CHECK_THROWS_AS(at_input_boundary("a", [] { throw std::runtime_error("other"); }), std::runtime_error);
  CHECK_THROWS_AS(at_input_boundary("a", [] { throw std::logic_error("bug"); }), std::logic_error);
  CHECK(at_input_boundary("a", [] { return 7; }) == 7);
}

TEST_CASE("core: a JSON type error and a bare 'stod' name the input (issue 33)") {
  // nlohmann::json's own exception, as a reader that trusted a value's type let it escape:
  // "[json.exception.type_error.302] type must be string, but is number" reached the user, exit 1.
  CHECK(input_error_of([] {
          const nlohmann::json j = {{"parent", 5}};
          (void)j.at("parent").get<std::string>();
        }) == "answers.csv: a JSON value of the wrong type or shape: type must be string, but is number");
  // std::stod's exceptions say only "stod".
  CHECK(input_error_of([] { (void)std::stod("1e-400x"); }) ==
        "answers.csv: a number in it is not a number or out of range (std::stod)");
  CHECK(input_error_of([] { (void)std::stoi("x"); }) ==
        "answers.csv: a number in it is not a number or out of range (std::stoi)");
  CHECK_THROWS_AS(at_input_boundary("a", [] { throw std::out_of_range("vector::at"); }), std::out_of_range);
}

}  // namespace test_library_error
