# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes a file whole or not at all: written beside it ("<path>.part"), flushed to the
disk and moved in, so a crash or an error mid-write leaves the previous file as it was
(the journals of runs and of participant records, which exist to survive crashes, and
every CSV an export writes over a file the user chose)."""
import contextlib
import errno
import json
import os
import shutil


@contextlib.contextmanager
def replacing(path, newline=None):
    """``with replacing(path) as handle:`` a UTF-8 text file to write that becomes ``path``
    when the block ends, and is removed, ``path`` untouched, when it raises. ``newline`` as
    open()'s (csv wants ""). A symbolic link stays one: the file it points to is written
    (moving the new file onto the link replaced the link). A file there keeps its
    permissions, and one the user may not write is refused (PermissionError) rather than
    replaced, which the folder's permission alone would allow. Raises OSError (named by
    ``path``, or its ``.part``, which callers that show it name without the suffix)."""
    target = os.path.realpath(path)
    existing = os.path.isfile(target)
    if existing and not os.access(target, os.W_OK):
        raise PermissionError(errno.EACCES, "the file is read-only for you, so it was not written over", path)
    temporary = target + ".part"
    try:
        with open(temporary, "w", newline=newline, encoding="utf-8") as handle:
            yield handle
            handle.flush()
            if existing:
                shutil.copymode(target, temporary)
            os.fsync(handle.fileno())
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(temporary)
        raise


def write_json(path, state):
    """Writes ``state`` as JSON to ``path`` (its folder made if needed). Raises OSError."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with replacing(path) as handle:
        json.dump(state, handle)
