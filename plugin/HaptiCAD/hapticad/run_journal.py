# SPDX-License-Identifier: GPL-3.0-or-later
"""A similarity run in progress, written to disk after every answer, so that a crash
(FreeCAD's, the machine's) loses no participant's answers: the document holds a run only
once it is kept, and is saved only when the designer saves it.

One JSON file per study of a saved document, in FreeCAD's user data folder
(``HaptiCAD/runs``), named from the document's path and the study's name; it holds the
participant, the seed, the trials and answers so far, and what the run was felt on. A
run is resumed only on the study as it was (the same trials from the same seed, the same
stimuli and context): ``resumable`` says why not otherwise. The file goes when the run
is kept or stopped. App-only.
"""
import hashlib
import json
import os

import FreeCAD as App

from . import similarity_study as ss


def path_for(study):
    """Where ``study``'s run in progress is written, or None for a document never saved
    (no path to tell it from another's)."""
    doc_path = study.Document.FileName
    if not doc_path:
        return None
    key = hashlib.sha1(f"{os.path.abspath(doc_path)}\n{study.Name}".encode()).hexdigest()[:16]
    return os.path.join(App.getUserAppDataDir(), "HaptiCAD", "runs", f"{key}.json")


def write(study, run):
    """Writes ``run`` (answers so far) beside nothing the designer sees; atomically, so
    a crash mid-write leaves the previous answers."""
    path = path_for(study)
    if path is None:
        return
    os.makedirs(os.path.dirname(path), exist_ok=True)
    state = {"document": os.path.abspath(study.Document.FileName), "study": study.Name,
             "name": run.participant, "seed": run.seed, "started": run.started,
             "trials": [[t.kind, t.first, t.second] for t in run.trials], "answers": list(run.answers),
             "stimuli": run.stimuli, "context": run.context}
    temporary = path + ".part"
    with open(temporary, "w", encoding="utf-8") as handle:
        json.dump(state, handle)
        handle.flush()
        os.fsync(handle.fileno())
    os.replace(temporary, path)


def read(study):
    """The run in progress written for ``study``, as written, or None."""
    path = path_for(study)
    if path is None or not os.path.exists(path):
        return None
    try:
        with open(path, encoding="utf-8") as handle:
            state = json.load(handle)
    except (OSError, ValueError):
        return None
    return state if isinstance(state, dict) and state.get("answers") else None


def forget(study):
    """The run is kept or stopped: its file goes."""
    path = path_for(study)
    if path is not None and os.path.exists(path):
        os.remove(path)


def _as_written(value):
    return json.loads(json.dumps(value))  # tuples become lists, as the file has them


def resumable(study, state):
    """"" when ``state`` can go on on ``study`` as it is now, else why not."""
    if state.get("stimuli") != _as_written(ss.stimuli(study)):
        return "the study's stimuli changed since"
    if state.get("context") != _as_written(ss.felt_context(study)):
        return "the surface or a reference changed since"
    return ""


def resume(study, state):
    """The run of ``state`` on ``study``, its answers back. Raises ValueError saying why
    it cannot go on (resumable), or when the seed no longer gives the same trials."""
    why = resumable(study, state)
    if why:
        raise ValueError(f"{state.get('name')}'s run cannot go on: {why}")
    run = ss.Run(study, state["name"], seed=state["seed"])
    if [[t.kind, t.first, t.second] for t in run.trials] != state["trials"]:
        raise ValueError(f"{state.get('name')}'s run cannot go on: its trials were drawn by another version")
    run.started = state.get("started", run.started)
    run.answers = list(state["answers"])
    return run
