"""The errors a user can act on; the command line prints them in one line and exits 2."""


class OutputError(OSError):
    """The target cannot be written (exists, unwritable, disk full); nothing was left behind."""
