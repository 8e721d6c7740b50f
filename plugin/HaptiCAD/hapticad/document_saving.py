# SPDX-License-Identifier: GPL-3.0-or-later
"""Saving a document that a command line read (``hapticad fit-texture --apply``) back in
its file, without FreeCAD's GUI, losing nothing:

    read = fingerprint(path)          # before the document is opened
    doc = App.openDocument(path) ...  # the work
    save_in_place(doc, read)          # ValueError, nothing saved, if it cannot be done safely

- Another program's save in between (a second ``hapticad`` on the same file, FreeCAD's GUI)
  is not written over: two ``--apply`` runs at once each said "set" and one change was
  lost. The check and the save are made under an exclusive lock on the document's folder,
  so two hapticad processes take turns; the one that comes second finds the file changed.
- A file the user cannot write is refused (FreeCAD would replace a read-only file in a
  writable folder), and a folder it cannot write in is said in words (FreeCAD raised a
  dict of its exception's fields).
- What only the GUI writes (GuiDocument.xml: visibility, colours, the thumbnail) is put
  back as the file held it: saved without it, the document opened with every part hidden.

No GUI needed; tested headless (tests/plugin/hapticad/test_document_saving.py).
"""
import contextlib
import fcntl
import hashlib
import os
import zipfile


def fingerprint(path):
    """What tells the file at ``path`` apart from any later save of it: its size and the
    SHA-256 of its bytes (a modification time can repeat within its resolution).
    Raises OSError."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return os.path.getsize(path), digest.hexdigest()


@contextlib.contextmanager
def _folder_locked(folder):
    """An exclusive flock on ``folder`` for the block (released when it ends or the
    process dies); another hapticad saving in the same folder waits for it."""
    descriptor = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX)
        yield
    finally:
        os.close(descriptor)  # releases the lock


def _check_writable(path):
    folder = os.path.dirname(path) or "."
    if not os.access(path, os.W_OK):
        raise ValueError(f"{path}: the file is read-only for you; nothing was saved (make it writable, "
                         "or copy it and give the copy)")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ValueError(f"{path}: its folder {folder} cannot be written in, and FreeCAD saves through a "
                         "new file beside it; nothing was saved")


def check_savable(path):
    """Raises ValueError, saying why, when save_in_place could not write ``path`` (read-only
    file or folder): for a command to say before its work, not after."""
    _check_writable(os.path.abspath(path))


def save_in_place(doc, read_fingerprint):
    """Saves ``doc`` in its file (``doc.FileName``) if the file is still what
    ``read_fingerprint`` (fingerprint() before the document was opened) found, keeping the
    GUI's part of it. Raises ValueError, the file untouched, when another program saved it
    meanwhile, or it or its folder cannot be written."""
    path = os.path.abspath(doc.FileName)
    with _folder_locked(os.path.dirname(path)):
        if fingerprint(path) != read_fingerprint:
            raise ValueError(f"{path}: another program saved the document after it was read here; nothing was "
                             "saved, so that save is kept: run the command again to apply to it")
        _check_writable(path)
        with zipfile.ZipFile(path) as archive:
            before = {info.filename: archive.read(info) for info in archive.infolist()}
        try:
            doc.save()
        except Exception as exc:  # Base.FileException: a dict of its fields as its text
            detail = exc.args[0] if exc.args else exc
            reason = detail.get("sErrMsg", "") if isinstance(detail, dict) else str(detail)
            raise ValueError(f"{path}: FreeCAD could not save it ({reason or type(exc).__name__}); "
                             "the file is as it was") from None
        with zipfile.ZipFile(path) as archive:
            written = set(archive.namelist())
        kept = {name: data for name, data in before.items() if name not in written}
        if kept:
            with zipfile.ZipFile(path, "a", zipfile.ZIP_DEFLATED) as archive:
                for name, data in kept.items():
                    archive.writestr(name, data)
