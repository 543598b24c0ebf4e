"""Small text files (reports, tables, catalogs) written atomically; imports nothing heavy."""
from __future__ import annotations

import os
from pathlib import Path

from .errors import OutputError


def write_text(path: Path, text: str) -> None:
    """Atomically: a temporary beside the target, renamed onto it when complete; a failure is one
    OutputError naming the path."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, path)
    except OSError as exc:
        raise OutputError(f"{path}: {exc.strerror or exc}") from None
    finally:
        tmp.unlink(missing_ok=True)
