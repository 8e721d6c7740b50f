# SPDX-License-Identifier: GPL-3.0-or-later
"""What HaptiCAD's Python proxies save in the document, and the properties and checks
every HaptiCAD object shares (its type tag, hidden bookkeeping, "is it being restored").

FreeCAD 0.20 with Python 3.11 pickles a proxy through both protocols, ``dumps``/
``loads`` and ``__getstate__``/``__setstate__``; a proxy without all four makes
reopening print "setAttr failed" (field notes). No GUI.
"""


class SchemaState:
    """A document object's proxy: it saves only the schema version it was written with
    (``SCHEMA``, set by the class), which ``onDocumentRestored`` can migrate from."""

    SCHEMA = 1

    def dumps(self):
        return {"schema": self.SCHEMA}

    def loads(self, state):
        self.schema = (state or {}).get("schema", self.SCHEMA)

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)


class NoState:
    """A view provider that keeps no state of its own in the document."""

    def dumps(self):
        return None

    def loads(self, state):
        return None

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


def add_type_tag(obj, type_tag):
    """The hidden ``HaptiCADType`` string by which HaptiCAD finds its objects."""
    if "HaptiCADType" not in obj.PropertiesList:
        obj.addProperty("App::PropertyString", "HaptiCADType", "Base", "Type tag of HaptiCAD objects")
        obj.setEditorMode("HaptiCADType", 2)  # hidden
    obj.HaptiCADType = type_tag


def add_properties(obj, properties):
    """Adds the properties an object lacks, each (name, kind, group, tooltip, default,
    constraint): a constraint (min, max, step) makes a constrained value of the default.
    A document does not save constraint ranges: call this on every restore too, so the
    ranges hold again (a value saved outside one is brought within it, and said so)."""
    for name, kind, group, tip, default, constraint in properties:
        if name in obj.PropertiesList:
            if constraint is not None:
                saved = getattr(obj, name)
                setattr(obj, name, (saved, *constraint))
                if getattr(obj, name) != saved:
                    import FreeCAD as App

                    App.Console.PrintWarning(f"{obj.Label}: {name} {saved:g} was outside {constraint[0]:g}.."
                                             f"{constraint[1]:g}; it is {getattr(obj, name):g} now\n")
            continue
        obj.addProperty(kind, name, group, tip)
        if constraint is not None:
            setattr(obj, name, (default, *constraint))
        elif default is not None:
            setattr(obj, name, default)


def add_hidden_state(obj, entries, group="Base"):
    """Hidden string properties, (name, tooltip) each, for an object's own bookkeeping."""
    for name, tip in entries:
        if name not in obj.PropertiesList:
            obj.addProperty("App::PropertyString", name, group, tip)
            obj.setEditorMode(name, 2)


def is_restoring(obj):
    """Loading, or undoing / redoing: every property comes back as it was, and one must
    not set others from it (undoing a material change would reset an overridden mu)."""
    return "Restore" in obj.State or obj.Document.Restoring or obj.Document.Transacting


def is_alive(obj):
    """False once a document object (or a document) is deleted: its Python object
    outlives it."""
    try:
        return bool(obj.Name)
    except Exception:  # noqa: BLE001 (FreeCAD raises its own error for a deleted object)
        return False
