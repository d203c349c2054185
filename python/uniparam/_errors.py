"""The exceptions of uniparam, mirroring the C++ library's (core/error.hpp).

Every failure of a computation is one of these; the library never returns an
uncertified number in place of a result.
"""


class Error(Exception):
    """Base of every uniparam exception (C++ uniparam::Error)."""


class ParseError(Error, ValueError):
    """Text that is not a valid curve, expression or number.

    ``column`` is the 1-based column where the problem was detected and
    ``expected`` a short description of what would have been valid there.
    """

    def __init__(self, message, column=0, expected=""):
        super().__init__(message)
        self.column = column
        self.expected = expected


class DomainError(Error, ArithmeticError):
    """A well-formed request whose mathematics is undefined (a pole in [0, 1],
    a constant curve, the angular speed of a straight line where it matters)."""


class InvalidArgument(Error, ValueError):
    """A well-formed request outside what an option allows."""


class BudgetExceeded(Error):
    """A value that could not be certified within a budget (precision,
    degree, size); the message names the limit and the option that raises it."""


class TimeLimitExceeded(BudgetExceeded, TimeoutError):
    """The ``timeout=`` of the call ran out (C++ TimeLimitExceeded)."""


class TargetNotReachedWarning(UserWarning):
    """A C1 map (``target=``) missed its target uniformity: the best map found
    is returned (the CLI's exit status 4)."""


for _cls in (Error, ParseError, DomainError, InvalidArgument, BudgetExceeded, TimeLimitExceeded,
             TargetNotReachedWarning):
    _cls.__module__ = "uniparam"  # shown as uniparam.ParseError
del _cls
