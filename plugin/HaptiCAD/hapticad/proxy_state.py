# SPDX-License-Identifier: GPL-3.0-or-later
"""What HaptiCAD's Python proxies save in the document, in one place.

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
