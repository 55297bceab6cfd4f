"""Every error robotdesc raises on purpose: one root, `RobotdescError`, and its two branches.

`InputError` (exit code 2) means the input could not be checked: malformed XML, an unknown
package, a mesh that cannot be read, a limit hit, a usage error. A `RobotdescError` that is
not an `InputError` (`RuleCrashed`, `WorkerCrashed`) is a bug (exit code 3), as is anything
else that escapes.

The errors of a bad argument value (`OptionError`, `SettingError`, `GeometryError`,
`UnknownLinkError`) are also `ValueError`s, Python's convention for such values, so that code
catching `ValueError` around a call keeps working.

Every class here pickles with its fields (errors travel back from worker processes).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Any

from robotdesc.source import Provenance, Span


class RobotdescError(Exception):
    """Root of every error robotdesc raises on purpose."""

    exit_code: int = 3

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle with the fields, whatever the subclass's constructor takes."""
        return (_rebuild, (type(self), self.args, dict(self.__dict__)))


def _rebuild(cls: type[RobotdescError], args: tuple[Any, ...],
             state: dict[str, Any]) -> RobotdescError:
    """An error unpickled: its class, `args` and fields restored without its constructor."""
    error = cls.__new__(cls)
    error.args = args
    error.__dict__.update(state)
    return error


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


class InvalidAnswer(SandboxViolation):
    """The xacro worker's answer does not have the shape the worker writes, or names a path
    the parent cannot justify (exit 2; nothing of the answer is used or shown)."""


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


# --- meshes -------------------------------------------------------------------------------


class MeshErrorKind(str, enum.Enum):
    """Why a mesh file could not be read."""

    LFS_POINTER = "lfs-pointer"
    TRUNCATED = "truncated"
    TOO_LARGE = "too-large"
    NON_FINITE = "non-finite"
    BAD_INDEX = "bad-index"
    MALFORMED = "malformed"
    EMPTY = "empty"
    UNSUPPORTED = "unsupported-format"
    BAD_SCALE = "bad-scale"
    UNREADABLE = "unreadable"


class MeshError(InputError):
    """A mesh file is malformed, oversized or not a mesh at all.

    Args:
        kind: the machine-readable reason.
        message: what is wrong, in a user's words (the file name is prepended).
        path: the mesh file.
        span: where the `<mesh>` element is, when the caller knows it.

    Attributes:
        kind, path: as given; detail: the message without the file name.
    """

    def __init__(self, kind: MeshErrorKind, message: str, path: str = "",
                 span: Span | None = None) -> None:
        text = f"{path}: {message}" if path else message
        super().__init__(text, span)
        self.kind = kind
        self.path = path
        self.detail = message


class GeometryError(InputError, ValueError):
    """A geometry cannot be used: a primitive dimension that is not positive and finite, a
    mesh without triangles, a surface enclosing no volume.

    Args:
        message: what is wrong, in a user's words.
        span: where the geometry is written, when known.
        shape: "box", "cylinder", "sphere", "capsule", "mesh", ... ("" when unknown).
        dimensions: the offending dimensions (m), for a primitive.
    """

    def __init__(self, message: str, span: Span | None = None, *, shape: str = "",
                 dimensions: tuple[float, ...] = ()) -> None:
        super().__init__(message, span)
        self.shape = shape
        self.dimensions = dimensions


class NoVolumeError(GeometryError):
    """Points span no volume (fewer than four distinct, or all coplanar): no hull."""


# --- options and settings -----------------------------------------------------------------


class OptionError(UsageError, ValueError):
    """An option of a command or of an API call has a value out of range or unknown.

    Args:
        option: the option's name as the API spells it ("ratio", "max_hulls", ...).
        value: the value given.
        message: what is wrong, in a user's words.
    """

    def __init__(self, option: str, value: object, message: str) -> None:
        super().__init__(message)
        self.option = option
        self.value = value


class CollisionOptionError(OptionError):
    """An option of collision generation (`CollisionOptions`, an engine limit, a method or
    decimation engine's name) is out of range or unknown."""


class SimOptionError(OptionError):
    """An option of the physics checks (scene, settle, hold, drive, engine, collision
    variant) is out of range or unknown."""


class SettingError(ConfigError, ValueError):
    """A configuration setting (robotdesc.toml, `[meshes]`) has a value out of range; the
    config reader adds the file and line.

    Args:
        key: the setting as the config spells it ("mass-tolerance").
        value: the value given.
        message: what is wrong, in a user's words.
    """

    def __init__(self, key: str, value: object, message: str) -> None:
        super().__init__(message)
        self.key = key
        self.value = value


class UnknownLinkError(UsageError, ValueError):
    """Links were named that the robot does not have (with the geometry asked for).

    Args:
        links: the names not found.
        message: what is wrong, in a user's words.
    """

    def __init__(self, links: tuple[str, ...], message: str) -> None:
        super().__init__(message)
        self.links = links


# --- collision outputs --------------------------------------------------------------------


class OutputConflict(InputError):
    """An output would overwrite a file robotdesc did not write (or one a user edited).

    Args:
        message: what is wrong, in a user's words.
        span: the output folder or file concerned.
        files: the files in conflict, relative to the output folder ("" entries never).
    """

    def __init__(self, message: str, span: Span | None = None,
                 files: tuple[str, ...] = ()) -> None:
        super().__init__(message, span)
        self.files = files


# --- kinematics (Pinocchio) ---------------------------------------------------------------

#: What to tell a user who lacks Pinocchio.
PINOCCHIO_HINT = "install it with: pip install '.[kinematics]'  (the `pin` package)"


class KinematicsUnavailable(InputError):
    """Pinocchio (`pin`) is not installed, so kinematic checks cannot run (exit code 2).

    Args:
        what: the command or check that needs Pinocchio (the message starts with it).
    """

    def __init__(self, what: str) -> None:
        super().__init__(f"{what} needs Pinocchio, which is not installed; {PINOCCHIO_HINT}")
        self.what = what


@dataclass(frozen=True)
class BuildProblem:
    """Why Pinocchio could not build a model.

    Attributes:
        reason: Pinocchio's (urdfdom's) own words, its source locations removed.
        element: the element the reason names ("joint:j", "link:l"), "" when none.
        where: that element's provenance, when known.
        from_pinocchio: False when robotdesc refused the model before calling Pinocchio
            (links that do not form one tree, which crash urdfdom on some inputs).
    """

    reason: str
    element: str = ""
    where: Provenance | None = None
    from_pinocchio: bool = True


class KinematicBuildError(InputError):
    """Pinocchio refused the robot; `problem` says why and where."""

    def __init__(self, problem: BuildProblem) -> None:
        prefix = "Pinocchio cannot build the model" if problem.from_pinocchio else \
            "the model cannot be given to Pinocchio"
        super().__init__(f"{prefix}: {problem.reason}",
                         problem.where.span if problem.where else None)
        self.problem = problem


# --- physics checks -----------------------------------------------------------------------


class SimUnavailable(InputError):
    """A physics engine is not installed, so the physics checks cannot run (exit 2).

    Args:
        engine: "mujoco" or "dart".
        requirement: what to install (a pip requirement).
        message: the install hint.
    """

    def __init__(self, engine: str, requirement: str, message: str) -> None:
        super().__init__(message)
        self.engine = engine
        self.requirement = requirement


class SimMeshError(InputError):
    """A mesh of the description cannot be given to the simulator (names the `<mesh>` line)."""


class SimModelError(InputError):
    """The robot cannot become a simulation model; names the link when one is to blame.

    Attributes:
        link: the offending link's name, or "" when no single link is to blame.
    """

    def __init__(self, message: str, span: Span | None = None, link: str = "") -> None:
        super().__init__(message, span)
        self.link = link


class DriveConfigError(InputError):
    """The drive joints cannot be found or do not fit the robot.

    Args:
        message: what is wrong, in a user's words.
        group: the drive group concerned ("" when none is).
        joint: the joint concerned ("" when none is).
    """

    def __init__(self, message: str, span: Span | None = None, *, group: str = "",
                 joint: str = "") -> None:
        super().__init__(message, span)
        self.group = group
        self.joint = joint


# --- bugs (exit code 3) -------------------------------------------------------------------


class RuleCrashed(RobotdescError):
    """A rule's check raised: a bug in robotdesc (exit code 3), named after the rule.

    Attributes:
        code, name: the rule's code and name; target: the file being linted.
    """

    def __init__(self, code: str, name: str, target: str, cause: BaseException) -> None:
        super().__init__(f"rule {code} ({name}) crashed on {target}: "
                         f"{type(cause).__name__}: {cause}")
        self.code, self.name, self.target = code, name, target


class WorkerCrashed(RobotdescError):
    """Linting a target raised something that is not an input error (a bug, exit code 3).

    Args:
        target: the target's name.
        summary: the exception's type and message.
        trace: its traceback, as text (it happened in another process).
    """

    def __init__(self, target: str, summary: str, trace: str) -> None:
        super().__init__(f"{summary} (while linting {target})\n{trace}")
        self.target = target
        self.summary = summary
        self.trace = trace
