# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes a JSON file whole or not at all: written beside it, flushed to the disk and
moved in, so a crash mid-write leaves the previous file (the journals of runs and of
participant records, which exist to survive crashes)."""
import json
import os


def write_json(path, state):
    """Writes ``state`` as JSON to ``path`` (its folder made if needed). Raises OSError."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    temporary = path + ".part"
    with open(temporary, "w", encoding="utf-8") as handle:
        json.dump(state, handle)
        handle.flush()
        os.fsync(handle.fileno())
    os.replace(temporary, path)
