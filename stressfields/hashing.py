"""The content and values hashes under their earlier import path, for scripts that name it
(``from stressfields.hashing import content_hash, values_hash``): they live in `output.hashing`,
and `file_hash`/`verify`, which read a file of any format, in `output.formats`."""
from .output.formats import file_hash, verify
from .output.hashing import ATTR, FORMS, content_hash, values_hash

__all__ = ["ATTR", "FORMS", "content_hash", "file_hash", "values_hash", "verify"]
