// cli/input.hpp -- command-line values that may name a file or standard input.
#pragma once

#include <cstddef>
#include <string>

namespace uniparam::cli {

/// The text of a command-line value that may be given indirectly:
/// * "-": all of standard input;
/// * "@FILE": the contents of FILE ("@" alone, or a FILE that cannot be
///   opened or read, is an error);
/// * anything else: the value itself.
/// `what` names the value in messages ("CURVE", "--control"), and
/// `limit_option`, when not empty, the option that raises max_bytes.
/// At most one value of a command may be "-": the caller checks.
/// \post the returned text has at most max_bytes bytes.
/// \throws InvalidArgument naming `what` (and the file, with strerror) when
///         the file or standard input cannot be read; for more than
///         max_bytes bytes, BudgetExceeded naming `limit_option` when one is
///         given (a limit the user can raise, exit code 4 like the curve
///         parser's --max-length), else InvalidArgument.
std::string read_argument_text(const std::string& what, const std::string& value, std::size_t max_bytes,
                               const std::string& limit_option = "");

/// True when `value` makes read_argument_text read standard input.
inline bool reads_stdin(const std::string& value) { return value == "-"; }

}  // namespace uniparam::cli
