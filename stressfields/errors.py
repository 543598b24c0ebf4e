"""The errors a user can act on (the command line prints them in one line and exits 2), and how
their messages show a value."""
import os
import reprlib

_SHOW = reprlib.Repr()
_SHOW.maxlevel, _SHOW.maxlist, _SHOW.maxdict, _SHOW.maxstring, _SHOW.maxother = 3, 8, 6, 60, 40


def show(value) -> str:
    """repr for messages, shortened: a recipe value may be a 1 MB list or nested 30 deep."""
    return _SHOW.repr(value)


class RecipeError(ValueError):
    """An invalid recipe; ``problems`` lists every message."""

    def __init__(self, problems: list[str], source: str = "recipe"):
        self.problems = problems
        self.source = source
        super().__init__(f"{source}: " + "; ".join(problems))

    def __str__(self) -> str:
        lines = [f"{self.source} is not valid:"] + [f"  - {p}" for p in self.problems]
        return "\n".join(lines)


class OutputError(OSError):
    """The target cannot be written (exists, unwritable, disk full); nothing was left behind."""


def name_problem(name: str) -> str | None:
    """Why a file name given as text cannot be used here (None if it can): a NUL byte, or a name
    that is not UTF-8 text (a command-line argument of other bytes arrives with lone surrogates,
    which neither the NetCDF library nor a UTF-8 terminal can take). Messages then show the name
    with ascii()."""
    if "\0" in name:
        return "the name holds a NUL byte (\\0); a file name cannot"
    try:
        name.encode("utf-8")
        os.fsencode(name)
    except UnicodeEncodeError:
        return "the name is not UTF-8 text; rename the file"
    return None
