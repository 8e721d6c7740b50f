# SPDX-License-Identifier: GPL-3.0-or-later
"""Participants recorded in a stiffness study since its document was last saved,
written to disk as they come, so that a crash (FreeCAD's, the machine's) or a close
without saving loses none: a record is in the document at once, but on disk only once
the designer saves it.

One JSON file per study of a saved document, in FreeCAD's user data folder
(``HaptiCAD/cohorts``), named from the document's path and the study's name and ID
(which a document keeps: a later study given a deleted one's name is another). While the
study holds records its saved file does not, the file holds ``cohort``, every record the
study holds (rewritten after every change of it: a record, an import, a removal, an Undo
or Redo), and ``lost``, the records an earlier session recorded and never saved that
have not been put back or dropped yet. When the document is opened again, the records
the file holds and the document does not are offered back (``lost``); a save holding
them lets them go (``SaveWatcher``), and the file goes once nothing in it is unsaved. A
document never saved has no path to tell it from another's: nothing is written for it
(``never_saved``).

What this session knows of a study (the cohort its saved file holds, the records lost
before it) lives on the study's proxy, which the document does not save: a document
closed and opened again is a new session. Records are compared as stored (their JSON,
keys sorted), as many times as they are held. App-only.
"""
import collections
import hashlib
import json
import os

import FreeCAD as App

from . import cohort
from .atomic_file import write_json


def _folder():
    return os.path.join(App.getUserAppDataDir(), "HaptiCAD", "cohorts")


def _document_key(doc_path):
    return hashlib.sha1(os.path.abspath(doc_path).encode()).hexdigest()[:16]


def _path(doc_path, study):
    study_key = hashlib.sha1(f"{study.Name}\n{study.ID}".encode()).hexdigest()[:12]
    return os.path.join(_folder(), f"{_document_key(doc_path)}-{study_key}.json")


def path_for(study):
    """Where ``study``'s unsaved records are written, or None for a document never saved."""
    doc_path = study.Document.FileName
    return _path(doc_path, study) if doc_path else None


def never_saved(study):
    """True when the study's document has no file yet: its records are nowhere on disk."""
    return not study.Document.FileName


class _Session:
    """What this session knows of one study: ``saved``, the records (as stored) its
    document's file holds, counted; ``lost``, those an earlier session recorded and did
    not save, not dropped; ``path``, the document's path the file was last written for;
    ``failure``, why the last write failed ("" when it did not)."""

    def __init__(self, saved=(), lost=(), path=""):
        self.saved = collections.Counter(saved)
        self.lost = list(lost)
        self.path = path
        self.failure = ""


def _session(study):
    """The study's session, made on first use (a study made in this session, or one
    whose proxy was made again: an undone deletion). Not known to be saved, its records
    count as unsaved: written more than needed, never fewer."""
    proxy = study.Proxy
    session = getattr(proxy, "_journal_session", None)
    if session is None:
        session = _Session(path=study.Document.FileName or "")
        proxy._journal_session = session
    return session


def _stored(study):
    """The study's records as stored (canonical JSON texts), in order; [] when its cohort
    cannot be read (the panel says so; nothing is written from it)."""
    try:
        data = json.loads(study.Cohort or "[]")
    except ValueError:
        return None
    if not isinstance(data, list):
        return None
    return [_canonical(d) for d in data]


def _canonical(data):
    return json.dumps(data, sort_keys=True)


def _minus(items, taken):
    """``items`` (a list) without ``taken`` (a Counter), each taken once per count, in order."""
    left = collections.Counter(taken)
    kept = []
    for item in items:
        if left[item] > 0:
            left[item] -= 1
        else:
            kept.append(item)
    return kept


def _offered(session, held):
    """The lost records not put back: those ``held`` (the cohort now, as stored) holds
    beyond what its file holds are put back (a lost record alike to a saved one is still
    lost: the file held both)."""
    return _minus(session.lost, collections.Counter(_minus(held, session.saved)))


def _read(path):
    """(study ID, the records the file at ``path`` holds, as stored); (None, []) when
    there is no file or it cannot be read (cut off by a crash mid-write: it is written
    beside and moved in, so only by hand)."""
    try:
        with open(path, encoding="utf-8") as handle:
            state = json.load(handle)
        # the older first: lost in an earlier session, then the cohort as it was last
        texts = [_canonical(d) for d in [*state.get("lost", []), *state.get("cohort", [])] if isinstance(d, dict)]
        return state.get("study_id"), texts
    except (OSError, ValueError, AttributeError, TypeError):
        return None, []


def opened(study):
    """The study's document was opened: what its file holds is its saved cohort, and the
    records its journal holds beyond them were lost unsaved (offered by ``lost``). Called
    by the study's proxy once the document is restored."""
    held = _stored(study) or []
    lost = []
    path = path_for(study)
    if path is not None:
        study_id, written = _read(path)
        if study_id in (None, study.ID):
            lost = _minus(written, collections.Counter(held))
    study.Proxy._journal_session = _Session(held, lost, study.Document.FileName)


def cohort_changed(study):
    """Writes the study's unsaved records after its cohort changed (a record, an import,
    a removal, an Undo or Redo of one): called by the study's proxy. Nothing for a document
    never saved. A failure to write is kept (``failure``) and warned of, never raised: the
    change itself is made."""
    if never_saved(study):
        return
    try:
        _write(study, _session(study))
    except OSError as exc:
        _session(study).failure = str(exc)
        App.Console.PrintWarning(f"HaptiCAD: {study.Label}: the participants recorded since the last save could "
                                 f"not be written to disk ({exc}): save the document\n")


def _write(study, session):
    """The file as the study and its session are now: written whole beside it and moved
    in (a crash mid-write leaves the previous one); removed when it would hold nothing."""
    path = _path(study.Document.FileName, study)
    held = _stored(study)
    if held is None:  # an unreadable cohort: the file as it was
        return
    lost = _offered(session, held)
    if not _minus(held, session.saved) and not lost:  # nothing that is not on disk
        if os.path.exists(path):
            os.remove(path)
        session.failure = ""
        return
    # the whole cohort, not only what is unsaved: the records it holds as often as it does
    # (one saved and one not of two alike are one lost, which the unsaved alone would not tell)
    state = {"document": os.path.abspath(study.Document.FileName), "study": study.Name, "study_id": study.ID,
             "label": study.Label, "cohort": [json.loads(t) for t in held], "lost": [json.loads(t) for t in lost]}
    write_json(path, state)
    session.failure = ""


def failure(study):
    """Why the unsaved records could not be written the last time, or ""."""
    return _session(study).failure


def lost(study):
    """The records recorded in ``study`` in an earlier session and never saved (the
    document was closed without saving, or FreeCAD ended) that it does not hold now, as
    cohort.Record, in the order they were recorded. Put back by adding them to the study
    (stiffness_study.add_records); forgotten by ``drop``."""
    found = []
    for text in _offered(_session(study), _stored(study) or []):
        try:
            found.append(cohort.from_dict(json.loads(text)))
        except (ValueError, TypeError):  # not a record (edited by hand): not offered
            pass
    return found


def drop(study, records):
    """Forgets ``records`` (of ``lost``) for good: the designer dropped them. Raises
    OSError if the file cannot be rewritten (they are still offered then)."""
    session = _session(study)
    dropped = collections.Counter(_canonical(r.as_dict()) for r in records)
    remaining = _minus(session.lost, dropped)
    if never_saved(study):
        session.lost = remaining
        return
    before, session.lost = session.lost, remaining
    try:
        _write(study, session)
    except OSError:
        session.lost = before
        raise


def saved(study, doc_path):
    """The study's document was saved as ``doc_path``: what it holds now is on disk, so
    its file keeps only the lost records not put back (or goes); the file written for
    another path before (a Save As) goes."""
    session = _session(study)
    held = _stored(study)
    if held is None:  # unreadable: nothing is taken as saved
        return
    previous = session.path
    session.lost = _offered(session, held)  # those put back are saved now
    session.saved = collections.Counter(held)
    session.path = doc_path
    if previous and os.path.abspath(previous) != os.path.abspath(doc_path):
        try:
            os.remove(_path(previous, study))
        except OSError:
            pass
    try:
        _write(study, session)
    except OSError as exc:
        session.failure = str(exc)


def _is_stiffness_study(obj):
    from .stiffness_study import is_stiffness_study

    return is_stiffness_study(obj)


class SaveWatcher:
    """Lets the written records go once a save holds them; the files of studies deleted
    before the save go too (their records are in no document now). One is enough for all
    documents: ``watch_saves``."""

    def slotFinishSaveDocument(self, doc, path):
        if not doc.FileName or os.path.abspath(path) != os.path.abspath(doc.FileName):
            return  # a copy saved elsewhere: the document itself is as unsaved as before
        studies = [o for o in doc.Objects if _is_stiffness_study(o)]
        for study in studies:
            saved(study, path)
        keep = {os.path.basename(_path(path, s)) for s in studies}
        prefix = _document_key(path) + "-"
        try:
            names = os.listdir(_folder())
        except OSError:
            return
        for name in names:
            if name.startswith(prefix) and name.endswith(".json") and name not in keep:
                try:
                    os.remove(os.path.join(_folder(), name))
                except OSError:
                    pass


_WATCHER = []


def watch_saves():
    """Registers the SaveWatcher once."""
    if not _WATCHER:
        _WATCHER.append(SaveWatcher())
        App.addDocumentObserver(_WATCHER[0])
