#include "analysis/lmm_formula.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

[[noreturn]] void fail(const std::string& formula, const std::string& why) {
  throw InputError(SourceLocation{"--formula", 0, 0, formula}, why);
}

bool is_name(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
  });
}

// Splits on `sep` outside parentheses.
std::vector<std::string> split_top(const std::string& s, char sep) {
  std::vector<std::string> out;
  int depth = 0;
  std::string cur;
  for (char c : s) {
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (c == sep && depth == 0) {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(trim(cur));
  return out;
}

// Every non-empty subset of the crossed variables, as R expands a*b*c (a variable crossed with itself
// is itself, a*a = a). n variables make 2^n - 1 terms: refused from the count before any is built
// (issue 32: crossing 24-30 factors, or `method` 30 times, ran out of memory).
std::vector<ModelTerm> expand_crossing(std::vector<std::string> vars, const std::string& formula) {
  std::vector<std::string> distinct;
  for (const std::string& v : vars)
    if (std::find(distinct.begin(), distinct.end(), v) == distinct.end()) distinct.push_back(v);
  vars = distinct;
  if (vars.size() > kMaxCrossedVariables)
    fail(formula, "crossing " + std::to_string(vars.size()) + " variables with '*' makes 2^" +
                      std::to_string(vars.size()) + " - 1 terms, more than the limit of " +
                      std::to_string((size_t{1} << kMaxCrossedVariables) - 1) + " (" +
                      std::to_string(kMaxCrossedVariables) +
                      " variables); write the interactions the model needs with ':' instead");
  std::vector<ModelTerm> out;
  for (size_t mask = 1; mask < (size_t{1} << vars.size()); ++mask) {
    ModelTerm t;
    for (size_t i = 0; i < vars.size(); ++i)
      if (mask & (size_t{1} << i)) t.push_back(vars[i]);
    out.push_back(t);
  }
  return out;
}
}  // namespace

std::vector<ModelTerm> parse_fixed_terms(const std::string& rhs, bool& intercept,
                                         const std::string& formula) {
  std::vector<ModelTerm> terms;
  std::string text = rhs;
  // "-1" removes the intercept; no other subtraction is supported.
  for (size_t pos; (pos = text.find("-")) != std::string::npos;) {
    if (trim(text.substr(pos + 1)).rfind("1", 0) != 0) fail(formula, "only '- 1' may be subtracted");
    intercept = false;
    text.erase(pos, text.find('1', pos) - pos + 1);
  }
  for (const auto& piece : split_top(text, '+')) {
    if (piece.empty()) continue;
    if (piece == "1") continue;
    if (piece == "0") {
      intercept = false;
      continue;
    }
    const bool crossing = piece.find('*') != std::string::npos;
    auto vars = split_top(piece, crossing ? '*' : ':');
    for (const auto& v : vars)
      if (!is_name(v)) fail(formula, "unsupported term '" + piece + "' (variables, ':' and '*' only)");
    if (crossing) {
      for (auto& t : expand_crossing(vars, formula)) terms.push_back(t);
    } else {
      terms.push_back(vars);
    }
  }
  // R's order: by the number of variables, then first appearance; duplicates (as sets) dropped.
  std::vector<ModelTerm> unique;
  std::set<std::set<std::string>> seen;
  for (const auto& t : terms)
    if (seen.insert(std::set<std::string>(t.begin(), t.end())).second) unique.push_back(t);
  std::stable_sort(unique.begin(), unique.end(),
                   [](const auto& a, const auto& b) { return a.size() < b.size(); });
  return unique;
}

LmmFormula parse_lmm_formula(const std::string& formula) {
  const auto tilde = formula.find('~');
  if (tilde == std::string::npos) fail(formula, "no '~' in the formula");
  LmmFormula f;
  f.response = trim(formula.substr(0, tilde));
  if (!is_name(f.response)) fail(formula, "the response must be one column name, got '" + f.response + "'");
  std::string fixed_text;
  for (const auto& piece : split_top(formula.substr(tilde + 1), '+')) {
    if (piece.size() >= 2 && piece.front() == '(' && piece.back() == ')') {
      const std::string inner = piece.substr(1, piece.size() - 2);
      if (inner.find("||") != std::string::npos)
        fail(formula, "'||' (uncorrelated effects) is not supported");
      const auto bar = inner.find('|');
      if (bar == std::string::npos) fail(formula, "parenthesised term without '|': '" + piece + "'");
      RandomTerm r;
      r.group = trim(inner.substr(bar + 1));
      if (!is_name(r.group)) fail(formula, "grouping factor must be one column name, got '" + r.group + "'");
      r.terms = parse_fixed_terms(inner.substr(0, bar), r.intercept, formula);
      if (!r.intercept && r.terms.empty()) fail(formula, "random term '" + piece + "' has no effect");
      f.random.push_back(r);
    } else {
      fixed_text += (fixed_text.empty() ? "" : " + ") + piece;
    }
  }
  f.fixed = parse_fixed_terms(fixed_text, f.intercept, formula);
  if (f.random.empty()) fail(formula, "no random-effects term '(... | group)'; use a linear model instead");
  return f;
}

std::vector<std::string> formula_variable_names(const std::string& formula) {
  std::vector<std::string> names;
  const auto name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
  };
  for (size_t i = 0; i < formula.size();) {
    if (!name_char(formula[i])) {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < formula.size() && name_char(formula[end])) ++end;
    const std::string token = formula.substr(i, end - i);
    size_t next = end;
    while (next < formula.size() && formula[next] == ' ') ++next;
    const bool function = next < formula.size() && formula[next] == '(';
    if (is_name(token) && !function && std::find(names.begin(), names.end(), token) == names.end())
      names.push_back(token);
    i = end;
  }
  return names;
}

}  // namespace crowdlab::analysis
