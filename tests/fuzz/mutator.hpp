#pragma once
// Seeded mutations of a valid input, the kinds the issue-21 fuzzer used: byte flips, truncations,
// duplications, splices, deletions, inserted odd bytes, numbers replaced by extreme ones, and deep
// nesting. Deterministic for a seed on every platform: the generator is std::mt19937_64 (its sequence
// is fixed by the standard) and every draw is taken from it by hand, not through a distribution.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace crowdlab::test {

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  /// A number in [0, n) (0 when n is 0).
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng_() % n); }

  /// `text` changed by one to three mutations; `deep` is what to insert for a deep nesting (its
  /// format's own: brackets for YAML/JSON, nested JOINTs for BVH). `name` receives what was done.
  std::string mutate(std::string text, const std::string& deep, std::string& name) {
    const std::size_t count = 1 + below(3);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t kind = below(9);
      name += (name.empty() ? "" : "+") + std::string(kKindNames[kind]);
      apply(kind, text, deep);
    }
    return text;
  }

 private:
  static constexpr const char* kKindNames[] = {"flip",   "truncate", "duplicate", "splice", "delete",
                                               "insert", "number",   "number",    "nesting"};

  std::size_t span(const std::string& t) { return 1 + below(std::min<std::size_t>(t.size(), 64) + 1); }

  void apply(std::size_t kind, std::string& t, const std::string& deep) {
    if (t.empty()) t = "x";
    const std::size_t at = below(t.size());
    switch (kind) {
      case 0:  // flip a few bits of a few bytes
        for (std::size_t i = 0, n = 1 + below(4); i < n; ++i) {
          const std::size_t byte = below(t.size());
          t[byte] = static_cast<char>(t[byte] ^ (1 << below(8)));
        }
        break;
      case 1:
        t.resize(at);
        break;
      case 2:
        t.insert(below(t.size() + 1), t.substr(at, span(t)));
        break;
      case 3: {  // a range replaced by a range from elsewhere in the file
        const std::string piece = t.substr(below(t.size()), span(t));
        t.replace(at, span(t), piece);
        break;
      }
      case 4:
        t.erase(at, span(t));
        break;
      case 5: {
        static const char* const kOdd[] = {"\0", "\xFF", "\xC3", "\r", "\"", "'", "\n",
                                           "\t", ",",    ":",    "-",  "{",  "]"};
        const char* odd = kOdd[below(std::size(kOdd))];
        t.insert(at, odd[0] ? std::string(odd) : std::string(1, '\0'));
        break;
      }
      case 6:
      case 7:
        replace_number(t);
        break;
      default:
        t.insert(at, deep);
    }
  }

  // Replaces the digits of a random number in the text by an extreme value.
  void replace_number(std::string& t) {
    static const char* const kExtreme[] = {
        "1e300", "-1e300", "65535", "4294967296",           "1e9",        "-1",  "0",        "nan",
        "inf",   "1e-9",   "-0",    "99999999999999999999", "2147483648", "1e7", "0.0000001"};
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (std::isdigit(static_cast<unsigned char>(t[i])) &&
          (i == 0 || !std::isdigit(static_cast<unsigned char>(t[i - 1]))))
        starts.push_back(i);
    if (starts.empty()) return;
    const std::size_t s = starts[below(starts.size())];
    std::size_t e = s;
    while (e < t.size() &&
           (std::isdigit(static_cast<unsigned char>(t[e])) || t[e] == '.' || t[e] == 'e' || t[e] == '-'))
      ++e;
    t.replace(s, e - s, kExtreme[below(std::size(kExtreme))]);
  }

  std::mt19937_64 rng_;
};

}  // namespace crowdlab::test
