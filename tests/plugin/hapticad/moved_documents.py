# SPDX-License-Identifier: GPL-3.0-or-later
"""Documents moved on disk, for the journals' tests (test_study_journal, test_run_journal):
folders made for them, and moves, as a file manager makes them. Not a test module."""
import os


def paths_in(top, folders, file_name="study.FCStd"):
    """``top``/FOLDER/``file_name`` for each of ``folders``, each folder made."""
    paths = [os.path.join(top, folder, file_name) for folder in folders]
    for path in paths:
        os.makedirs(os.path.dirname(path), exist_ok=True)
    return paths


def move_into(top, folder, paths, names):
    """Moves each of ``paths`` to ``top``/``folder``/its name of ``names`` (the folder
    made); the paths moved to, in order."""
    moved = [os.path.join(top, folder, name) for name in names]
    os.makedirs(os.path.join(top, folder), exist_ok=True)
    for path, to in zip(paths, moved):
        os.rename(path, to)
    return moved
