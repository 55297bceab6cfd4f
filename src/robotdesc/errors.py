"""The one root error of robotdesc and its two branches.

`InputError` (exit code 2) means the input could not be checked: malformed XML, an unknown
package, a limit hit, a usage error. Anything else that escapes is a bug (exit code 3).
"""

from __future__ import annotations

from robotdesc.source import Span


class RobotdescError(Exception):
    """Root of every error robotdesc raises on purpose."""

    exit_code: int = 3


class InputError(RobotdescError):
    """The input could not be checked. Carries where, when known.

    Args:
        message: what is wrong, in a user's words.
        span: the file, line and column the problem was found at, if known.
        call_stack: for errors inside a macro, the call sites (innermost first).
    """

    exit_code = 2

    def __init__(self, message: str, span: Span | None = None,
                 call_stack: tuple[Span, ...] = ()) -> None:
        super().__init__(message)
        self.message = message
        self.span = span
        self.call_stack = call_stack

    def __str__(self) -> str:
        where = f"{self.span}: " if self.span else ""
        chain = "".join(f"\n  in macro called from {site}" for site in self.call_stack)
        return f"{where}{self.message}{chain}"


class XmlSyntaxError(InputError):
    """The XML is not well-formed (or declares a DOCTYPE)."""


class ExpansionError(InputError):
    """Xacro could not expand the file (undefined property, bad macro call, ...)."""


class PackageNotFoundError(InputError):
    """A `$(find pkg)` or `package://pkg` names a package no resolver knows."""

    def __init__(self, package: str, span: Span | None = None,
                 searched: tuple[str, ...] = ()) -> None:
        looked = "; searched: " + ", ".join(searched) if searched else ""
        super().__init__(f"unknown package '{package}'{looked}", span)
        self.package = package
        self.searched = searched


class SandboxViolation(InputError):
    """The xacro file tried something safe mode forbids (escaping the package, os access)."""


class SandboxUnavailable(InputError):
    """The xacro worker cannot be confined on this system; untrusted expansion is refused."""


class LimitExceeded(InputError):
    """The expansion hit a time, memory, recursion or size limit."""


class ConfigError(InputError):
    """robotdesc's own configuration is invalid."""


class UsageError(InputError):
    """The command line was invalid (unknown rule code, bad argument)."""


class OutputError(InputError):
    """An output cannot be written where asked: the path is an input of the run, its folder
    is a file or read-only, or it would leave the output folder.

    Args:
        path: the output path as given.
        reason: why, in a user's words (the message is "cannot write PATH: REASON" unless
            `message` is given).
        message: the whole message, when it is not of that form.
    """

    def __init__(self, path: str, reason: str, message: str | None = None) -> None:
        super().__init__(message or f"cannot write {path}: {reason}")
        self.path = path
        self.reason = reason
