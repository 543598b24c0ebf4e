"""The errors a user can act on (the command line prints them in one line and exits 2), and how
their messages show a value."""
import reprlib

_SHOW = reprlib.Repr()
_SHOW.maxlevel, _SHOW.maxlist, _SHOW.maxdict, _SHOW.maxstring, _SHOW.maxother = 3, 8, 6, 60, 40


def show(value) -> str:
    """repr for messages, shortened: a recipe value may be a 1 MB list or nested 30 deep."""
    return _SHOW.repr(value)


class OutputError(OSError):
    """The target cannot be written (exists, unwritable, disk full); nothing was left behind."""
