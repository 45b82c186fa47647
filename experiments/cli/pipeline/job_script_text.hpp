#pragma once
// Values written into generated job scripts (`crowdlab plan`): each target language gets its own
// escaping, so that no spec name or path can run as code when the script runs (issue 21).
//   - shell (bash, GNU parallel lines, make recipes): single quotes, `'` as '\'' (POSIX sh quoting);
//   - make recipes additionally double every `$` (make expands `$` before the shell sees the line,
//     even under `make -n`, so `$(shell ...)` would run);
//   - Slurm `#SBATCH` directives are read by sbatch itself, with no quoting: values are reduced to
//     letters, digits, `.`, `_` and `-`;
//   - comments end at a newline, so control characters are replaced.
// Control characters (newline, carriage return, escape, ...) cannot be quoted for make or a Slurm
// directive at all: paths holding them are refused (require_script_safe).
#include <string>

namespace crowdlab::cli {

/// `s` as one POSIX shell word: 'text', with each ' written as '\''.
std::string shell_quote(const std::string& s);

/// `s` as one shell word inside a make recipe line: shell_quote(s) with every `$` doubled.
std::string make_recipe_quote(const std::string& s);

/// `s` reduced to [A-Za-z0-9._-] (runs of other bytes become one `_`), for a `#SBATCH` value.
std::string slurm_directive_word(const std::string& s);

/// `s` with every control character (bytes < 0x20 and 0x7f) replaced by `?`, for a `#` comment.
std::string comment_text(const std::string& s);

/// Throws InputError naming `option` when `value` holds a control character (newline, CR, ESC, ...).
void require_script_safe(const std::string& value, const std::string& option);

}  // namespace crowdlab::cli
