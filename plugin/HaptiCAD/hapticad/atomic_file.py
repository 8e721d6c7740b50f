# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes a file whole or not at all: written beside it ("<path>.part"), flushed to the
disk and moved in, so a crash or an error mid-write leaves the previous file as it was
(the journals of runs and of participant records, which exist to survive crashes, and
every CSV an export writes over a file the user chose)."""
import contextlib
import json
import os


@contextlib.contextmanager
def replacing(path, newline=None):
    """``with replacing(path) as handle:`` a UTF-8 text file to write that becomes ``path``
    when the block ends, and is removed, ``path`` untouched, when it raises. ``newline`` as
    open()'s (csv wants ""). Raises OSError (named by ``path``'s ``.part``, which callers
    that show it name without the suffix)."""
    temporary = path + ".part"
    try:
        with open(temporary, "w", newline=newline, encoding="utf-8") as handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(temporary, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(temporary)
        raise


def write_json(path, state):
    """Writes ``state`` as JSON to ``path`` (its folder made if needed). Raises OSError."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with replacing(path) as handle:
        json.dump(state, handle)
