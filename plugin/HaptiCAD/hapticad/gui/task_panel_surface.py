# SPDX-License-Identifier: GPL-3.0-or-later
"""Task panel that creates and edits a HapticSurface (and the vibration of its part).

Every property of the object gets a widget, built from surface_object.PROPERTIES by
its type (a property added there appears here without code): faces picked in the 3D
view (add, remove, list with their re-match status, highlight), the material with its
database values shown and overridable, the roughness category with its Ra range and
N-grades, the pattern (linear angle, circular centre picked in the view, curve from a
selected sketch or edges), texture presets and parameters, stiffness and friction, and
the part's vibration.

Edits go straight to the object, inside one transaction opened when the panel opens
(or by the command that created the surface): the overlay follows live, OK commits
everything as one undo step and Cancel reverts everything. Values are checked live by
the object's own validation (surface_object.validate, which includes the core's) and
the message is shown at the top; OK is refused while there is a problem.
"""
import html
import re

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtCore, QtGui, QtWidgets

from .. import (_core, face_picking, face_references, icon, materials, preferences, similarity_study,
               surface_compile, surface_object, texture_fit, vibration_object)
from ..other_edits import OtherEdits
from ..proxy_state import is_alive
from ..roughness_text import ra_band
from .busy_cursor import busy_cursor
from .document_closing import DocumentClosingObserver
from .narrow import SPIN_WIDTH_PX, let_narrow
from .selection import selected_curve
from .undo_redo_observer import UndoRedoObserver

# units shown after values, by property
UNITS = {
    "Stiffness": " N/mm", "Damping": " N·s/m", "StickSpeed": " mm/s", "TransitionSpeed": " mm/s", "StribeckSpeed": " mm/s",
    "PatternAngle": " °", "PatternBlendRadius": " mm", "TexturePeriod": " mm", "TextureFullRange": " N",
    "PatternCenter": " mm",
}
LABELS = {
    "StaticFriction": "Static friction μs", "DynamicFriction": "Dynamic friction μd",
    "RoughnessCategory": "Category", "FeelRoughness": "Feel the roughness grid",
    "PatternAngle": "Angle", "PatternCenter": "Centre (mm)", "PatternAxis": "Axis",
    "PatternCurve": "Curve", "AcrossFriction": "Across / along", "BackwardFriction": "Backward / forward",
    "TextureDC": "f_DC", "TextureViscosity": "f_vis", "TextureBeta": "β_h", "TextureAlpha": "α_h",
    "TextureBetaViscosity": "β_vis", "TextureAlphaViscosity": "α_vis", "TexturePeriod": "Period λ",
    "TextureFullRange": "Full range", "TextureScale": "Level 1 is",
    "RoughnessHeight": "Height × grid",
}
GROUP_TITLES = [("Surface", "Material"), ("Friction", "Friction and stiffness"), ("Roughness", "Roughness"),
                ("Pattern", "Friction pattern"), ("Texture", "Viscous texture")]
# widgets shown only when they apply
RELEVANT = {
    # the angle turns the linear stripes, the roughness grid and the texture's grating
    # (surface_compile.face_frame): hidden with a texture, an old angle turned it unseen
    "PatternAngle": lambda o: o.Pattern == "Linear" or o.FeelRoughness or o.Texture != "None",
    "PatternCenter": lambda o: o.Pattern == "Circular",
    "PatternAxis": lambda o: o.Pattern == "Circular",
    "PatternBlendRadius": lambda o: o.Pattern == "Circular",
    "PatternCurve": lambda o: o.Pattern == "Curve",
    "CurveEvaluation": lambda o: o.Pattern == "Curve",
    "CurveTableSize": lambda o: o.Pattern == "Curve",
    "Interpolation": lambda o: o.Pattern != "None",
    "AcrossFriction": lambda o: o.Pattern != "None",
    "BackwardFriction": lambda o: o.Pattern != "None",
    "RoughnessHeight": lambda o: o.FeelRoughness,
    "RoughnessFrictionModulation": lambda o: o.FeelRoughness,
    # the period shows with no texture too: a fit to recordings (the rows below it) reads it
    **{name: (lambda o: o.Texture != "None") for name in surface_object.TEXTURE_VALUES + ("TextureScale",)},
    "TextureFullRange": lambda o: o.Texture != "None" and o.TextureScale == "Device force",
}
FLOAT_DECIMALS = 4
SPECIAL = ("References", "Material", "RoughnessCategory", "PatternCurve")


def _label(name):
    return LABELS.get(name) or re.sub(r"(?<=[a-z])(?=[A-Z])", " ", name).capitalize()


def _dspin(low, high, step, suffix="", decimals=FLOAT_DECIMALS):
    box = QtWidgets.QDoubleSpinBox()
    box.setRange(low, high)
    box.setSingleStep(step)
    box.setDecimals(decimals)
    box.setSuffix(suffix)
    box.setKeyboardTracking(False)  # one edit per finished number, not per keystroke
    return box


def _with_component(vector, axis, value):
    """``vector`` (an App.Vector) with its ``axis`` ("x", "y" or "z") set to ``value``."""
    out = App.Vector(vector)
    setattr(out, axis, float(value))
    return out


class _Picker:
    """Selection observer: a click in the 3D view adds a face or picks the centre. Added
    unresolved (Gui.Selection.addObserver(picker, 0)): it is told the top-level object and
    the path to the face, so a face shown through a link is known for one."""

    def __init__(self, panel):
        self.panel = panel

    def addSelection(self, doc_name, obj_name, sub, point):
        self.panel.picked(doc_name, obj_name, sub, point)


class SurfaceTaskPanel:
    def __init__(self, surface):
        self.obj = surface
        self.doc = surface.Document
        # the creating command already opened the transaction; editing opens its own
        self._own_transaction = not self.doc.HasPendingTransaction
        if self._own_transaction:
            self.doc.openTransaction("Edit haptic surface")
        # Cancel restores these values; what was up to date with them is up to date again
        self.up_to_date = [o.Name for o in self.doc.Objects if "Touched" not in o.State]
        # similarity runs felt on this surface as it was: an edit that stops pooling them is said
        self.pooled_at_open = similarity_study.pooled_runs(self.doc)
        self.widgets = {}  # property (or "Prop.x") -> widget
        self.rows = {}  # property -> (label, field) to show or hide
        self.mode = "faces" if not surface.References else None
        self.problems = []
        self._loading = False
        self.form = [self._status_box(), self._faces_box()]
        for group, title in GROUP_TITLES:
            self.form.append(self._group_box(group, title))
        self.form.append(self._vibration_box())
        self.picker = _Picker(self)
        Gui.Selection.addObserver(self.picker, 0)
        # the document closing under the open panel: stop listening to clicks (it went on
        # asking the deleted surface for its name at every later click) and close
        self.closing = DocumentClosingObserver(self.doc, self.document_closing)
        # Cancel aborts the transaction, and with it whatever else was done meanwhile: asked first
        self.other_edits = OtherEdits(self.doc, self._edits_itself)
        # an Undo or Redo while open takes the transaction: shown again, and a new one at the next edit
        self._transaction_taken = False
        self.undo_redo = UndoRedoObserver(self.doc, self._undone_or_redone)
        # closed without OK or Cancel (Gui.Control.closeDialog()): the observers must not outlive it
        self.form[0].destroyed.connect(lambda _obj=None: self._stop_watching_others())
        self.set_mode(self.mode)  # the hint and the Add button say whether clicks add faces
        self.load()
        for box in self.form:
            let_narrow(box)

    # --- building -------------------------------------------------------------------

    def _box(self, title, icon_name="HaptiCAD_SurfaceObject"):
        box = QtWidgets.QWidget()
        box.setWindowTitle(title)
        box.setWindowIcon(QtGui.QIcon(icon(icon_name)))
        return box

    def _status_box(self):
        box = self._box("Haptic surface")
        layout = QtWidgets.QVBoxLayout(box)
        # named: the command opens the surface that tags a selected face already
        self.name_label = QtWidgets.QLabel()
        self.name_label.setObjectName("surfaceName")
        self.name_label.setWordWrap(True)
        layout.addWidget(self.name_label)
        self.status = QtWidgets.QLabel()
        self.status.setObjectName("status")
        self.status.setWordWrap(True)
        layout.addWidget(self.status)
        return box

    def _faces_box(self):
        box = self._box("Faces")
        layout = QtWidgets.QVBoxLayout(box)
        self.hint = QtWidgets.QLabel("Click faces in the 3D view to add them.")
        self.hint.setWordWrap(True)
        layout.addWidget(self.hint)
        self.faces = QtWidgets.QListWidget()
        self.faces.setObjectName("faces")
        self.faces.setSelectionMode(QtWidgets.QAbstractItemView.ExtendedSelection)
        self.faces.setMaximumHeight(120)
        self.faces.itemSelectionChanged.connect(self.highlight_selected)
        layout.addWidget(self.faces)
        buttons = QtWidgets.QHBoxLayout()
        self.add_button = QtWidgets.QPushButton("Add")
        self.add_button.setObjectName("addFaces")
        self.add_button.setCheckable(True)
        self.add_button.setToolTip("While pressed, faces you click in the 3D view are added")
        self.add_button.toggled.connect(self.set_adding)
        self.remove_button = QtWidgets.QPushButton("Remove")
        self.remove_button.setObjectName("removeFaces")
        self.remove_button.setToolTip("Remove the faces selected in the list")
        self.remove_button.clicked.connect(self.remove_selected_faces)
        buttons.addWidget(self.add_button)
        buttons.addWidget(self.remove_button)
        layout.addLayout(buttons)
        self.references = self.faces
        return box

    def _group_box(self, group, title):
        box = self._box(title)
        form = QtWidgets.QFormLayout(box)
        for name, kind, prop_group, tip, _, constraint in surface_object.PROPERTIES:
            if prop_group != group or name == "References":
                continue
            field = self._make_field(name, kind, constraint)
            field.setToolTip(tip)
            label = QtWidgets.QLabel(_label(name))
            label.setToolTip(tip)
            form.addRow(label, field)
            self.rows[name] = (label, field)
            if name == "Material":
                self.material_info = QtWidgets.QLabel()
                self.material_info.setObjectName("materialInfo")
                self.material_info.setWordWrap(True)
                reset = QtWidgets.QPushButton("Use the material's values")
                reset.setObjectName("resetMaterial")
                reset.clicked.connect(self.reset_to_material)
                self.reset_material = reset
                form.addRow(self.material_info)
                form.addRow(reset)
            elif name == "RoughnessCategory":
                self.roughness_info = QtWidgets.QLabel()
                self.roughness_info.setObjectName("roughnessInfo")
                self.roughness_info.setWordWrap(True)
                form.addRow(self.roughness_info)
        if group == "Texture":
            self._add_fit_rows(form)
        return box

    def _add_fit_options(self, form):
        """The fit's options as `hapticad fit-texture` takes them, folded away: the
        paper's values serve most recordings."""
        from .. import texture_fit_options as options

        self.fit_options_toggle = QtWidgets.QToolButton()
        self.fit_options_toggle.setObjectName("fitOptionsToggle")
        self.fit_options_toggle.setText("Fit options")
        self.fit_options_toggle.setCheckable(True)
        self.fit_options_toggle.setToolButtonStyle(QtCore.Qt.ToolButtonTextBesideIcon)
        self.fit_options_toggle.setArrowType(QtCore.Qt.RightArrow)
        self.fit_options_toggle.setAutoRaise(True)
        form.addRow(self.fit_options_toggle)
        self.fit_options = QtWidgets.QWidget()
        rows = QtWidgets.QFormLayout(self.fit_options)
        rows.setContentsMargins(12, 0, 0, 0)
        self.fit_tolerance = _dspin(*options.TOLERANCE_RANGE_PERCENT, 0.5, " %", 1)
        self.fit_tolerance.setObjectName("fitTolerance")
        self.fit_tolerance.setValue(options.DEFAULT_TOLERANCE_PERCENT)
        self.fit_tolerance.setToolTip("How far a section's speed may stray from a recorded speed and still be fitted "
                                      "(2.5 %, as the paper)")
        rows.addRow("Speed tolerance", self.fit_tolerance)
        self.fit_lowpass = _dspin(*options.LOWPASS_RANGE_HZ, 100, " Hz", 0)
        self.fit_lowpass.setObjectName("fitLowpass")
        self.fit_lowpass.setSpecialValueText("off")
        self.fit_lowpass.setValue(options.DEFAULT_LOWPASS_HZ)
        self.fit_lowpass.setToolTip("First-order low-pass on the recorded force before the spectrum (1000 Hz, as the "
                                    "paper's rig; off for a force already filtered)")
        rows.addRow("Low-pass", self.fit_lowpass)
        self.fit_harmonics = QtWidgets.QSpinBox()
        self.fit_harmonics.setObjectName("fitHarmonics")
        self.fit_harmonics.setRange(*options.HARMONICS_RANGE)
        self.fit_harmonics.setValue(options.DEFAULT_HARMONICS)
        self.fit_harmonics.setToolTip("Harmonic peaks of the grating fitted with the power law (3, as the paper)")
        rows.addRow("Harmonics", self.fit_harmonics)
        self.fit_min_periods = QtWidgets.QSpinBox()
        self.fit_min_periods.setObjectName("fitMinPeriods")
        self.fit_min_periods.setRange(*options.MIN_PERIODS_RANGE)
        self.fit_min_periods.setValue(options.DEFAULT_MIN_PERIODS)
        self.fit_min_periods.setSuffix(" periods")
        self.fit_min_periods.setToolTip("The shortest section of steady speed that is fitted (6 periods of the grating)")
        rows.addRow("Shortest section", self.fit_min_periods)
        self.fit_options.setVisible(False)
        form.addRow(self.fit_options)

        def fold(shown):
            self.fit_options.setVisible(shown)
            self.fit_options_toggle.setArrowType(QtCore.Qt.DownArrow if shown else QtCore.Qt.RightArrow)

        self.fit_options_toggle.toggled.connect(fold)

    def fit_option_values(self):
        """The fit's options as set, as texture_fit.fit_files takes them."""
        return {"tolerance_percent": float(self.fit_tolerance.value()), "lowpass_hz": float(self.fit_lowpass.value()),
                "harmonics": int(self.fit_harmonics.value()), "min_periods": int(self.fit_min_periods.value())}

    def _add_fit_rows(self, form):
        """Fit the texture to force recordings (seed 001 §III) at the grating period above."""
        self.fit_speeds = QtWidgets.QLineEdit(", ".join(f"{s:g}" for s in texture_fit.PAPER_SPEEDS_MM_S))
        self.fit_speeds.setObjectName("fitSpeeds")
        self.fit_speeds.setCursorPosition(0)  # a narrow panel shows "50, 80, ...", not "0, 80, ..."
        self.fit_speeds.setToolTip("The scanning speeds the recordings hold, mm/s: sections within the speed "
                                   "tolerance (Fit options; 2.5 %) of one of them are fitted")
        form.addRow(QtWidgets.QLabel("Recorded speeds"), self.fit_speeds)
        self._add_fit_options(form)
        button = QtWidgets.QPushButton("Fit to recordings…")
        button.setObjectName("fitTexture")
        button.setToolTip("Choose CSV recordings of strokes over a grating of period λ (a rig's time_s, "
                          "position_mm, lateral_force_n, or HaptiCAD traces): the texture's values are fitted "
                          "to them (seed 001 §III)")
        button.clicked.connect(self.choose_recordings)
        form.addRow(button)
        # the spectra and the lines through the speeds, as `hapticad fit-texture --plot` draws them
        self.fit_plot = QtWidgets.QPushButton("Plot the fit…")
        self.fit_plot.setObjectName("fitPlot")
        self.fit_plot.setToolTip("Save a picture of the last fit: each speed's spectrum with its harmonics and "
                                 "background, and f_DC, beta_h, alpha_h against speed (seed 001 Fig. 6)")
        self.fit_plot.setEnabled(False)
        self.fit_plot.clicked.connect(self.choose_plot)
        self.fit_report = None
        form.addRow(self.fit_plot)
        self.fit_info = QtWidgets.QLabel()
        self.fit_info.setObjectName("fitInfo")
        self.fit_info.setWordWrap(True)
        self.fit_info.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        form.addRow(self.fit_info)

    def _make_field(self, name, kind, constraint):
        obj = self.obj
        if name == "Material":
            combo = QtWidgets.QComboBox()
            combo.setObjectName(name)
            combo.currentTextChanged.connect(lambda text: self.set_property("Material", text))
            self.widgets[name] = combo
            return combo
        if name == "RoughnessCategory":
            combo = QtWidgets.QComboBox()
            combo.setObjectName(name)
            for row in _core.roughness_table():
                combo.addItem(_roughness_item(row), row.category)
            combo.currentIndexChanged.connect(lambda i: self.set_property(name, i + 1))
            self.widgets[name] = combo
            return combo
        if name == "PatternCurve":
            field = QtWidgets.QWidget()
            row = QtWidgets.QHBoxLayout(field)
            row.setContentsMargins(0, 0, 0, 0)
            self.curve_label = QtWidgets.QLabel()
            self.curve_label.setObjectName("curveLabel")
            button = QtWidgets.QPushButton("Use selection")
            button.setObjectName("useCurve")
            button.setToolTip("Select a sketch, or edges, in the 3D view or the tree, then press this")
            button.clicked.connect(self.use_selected_curve)
            row.addWidget(self.curve_label, 1)
            row.addWidget(button)
            return field
        if kind == "App::PropertyEnumeration":
            combo = QtWidgets.QComboBox()
            combo.setObjectName(name)
            combo.addItems(obj.getEnumerationsOfProperty(name))
            combo.currentTextChanged.connect(lambda text, n=name: self.set_property(n, text))
            self.widgets[name] = combo
            return combo
        if kind == "App::PropertyBool":
            check = QtWidgets.QCheckBox()
            check.setObjectName(name)
            check.toggled.connect(lambda on, n=name: self.set_property(n, bool(on)))
            self.widgets[name] = check
            return check
        if kind == "App::PropertyIntegerConstraint":
            spin = QtWidgets.QSpinBox()
            spin.setObjectName(name)
            spin.setRange(int(constraint[0]), int(constraint[1]))
            spin.setSingleStep(int(constraint[2]))
            spin.setKeyboardTracking(False)
            spin.valueChanged.connect(lambda v, n=name: self.set_property(n, int(v)))
            self.widgets[name] = spin
            return spin
        if kind in ("App::PropertyVector", "App::PropertyVectorDistance"):
            field = QtWidgets.QWidget()
            column = QtWidgets.QVBoxLayout(field)
            column.setContentsMargins(0, 0, 0, 0)
            row = QtWidgets.QHBoxLayout()
            column.addLayout(row)
            for axis in "xyz":
                spin = _dspin(-1e6, 1e6, 1.0, "", 3)
                spin.setObjectName(f"{name}.{axis}")
                spin.setToolTip(f"{axis}{UNITS.get(name, '')}")
                spin.valueChanged.connect(lambda _v, n=name, a=axis: self.set_vector(n, a))
                spin.setMinimumWidth(SPIN_WIDTH_PX)  # three side by side: narrower than their 1e6 range asks
                self.widgets[f"{name}.{axis}"] = spin
                row.addWidget(spin)
            if name == "PatternCenter":
                pick = QtWidgets.QPushButton("Pick")
                pick.setObjectName("pickCenter")
                pick.setToolTip("Then click the centre of the circles on the part in the 3D view")
                pick.clicked.connect(lambda: self.set_mode("centre"))
                column.addWidget(pick)  # under x, y, z: beside them the row is wider than the Combo View
            return field
        if kind == "App::PropertyAngle":
            spin = _dspin(-360.0, 360.0, 5.0, UNITS.get(name, ""), 2)
        elif kind == "App::PropertyFloatConstraint":
            spin = _dspin(constraint[0], constraint[1], constraint[2], UNITS.get(name, ""))
            if name == "TextureFullRange":  # 0 is no force: it stands for the device's full range
                spin.setSpecialValueText("device's full range")
        else:  # App::PropertyFloat
            spin = _dspin(-1e4, 1e4, 0.01, UNITS.get(name, ""))
        spin.setObjectName(name)
        spin.valueChanged.connect(lambda v, n=name: self.set_property(n, float(v)))
        self.widgets[name] = spin
        return spin

    def _vibration_box(self):
        box = self._box("Vibration of the part", "HaptiCAD_Vibration")
        form = QtWidgets.QFormLayout(box)
        self.vibrates = QtWidgets.QCheckBox("The part vibrates")
        self.vibrates.setObjectName("vibrates")
        self.vibrates.setToolTip("While the probe touches any face of this part and it is powered, the part "
                                 "vibrates (e.g. a shaver)")
        self.vibrates.toggled.connect(self.set_vibrates)
        # a surface may span faces of several parts: each part vibrates (or not) on its own
        self.vibration_part = QtWidgets.QComboBox()
        self.vibration_part.setObjectName("vibrationPart")
        self.vibration_part.currentIndexChanged.connect(lambda _i: None if self._loading else self.load())
        form.addRow("Part", self.vibration_part)
        form.addRow(self.vibrates)
        self.vibration_widgets = {}
        low, high = vibration_object.FREQUENCY_RANGE_HZ
        self.vibration_widgets["Frequency"] = _dspin(low, high, 10.0, " Hz", 1)
        low, high = vibration_object.AMPLITUDE_RANGE_N
        self.vibration_widgets["Amplitude"] = _dspin(low, high, 0.05, " N", 3)
        self.vibration_widgets["Powered"] = QtWidgets.QCheckBox()
        axis = QtWidgets.QWidget()
        row = QtWidgets.QHBoxLayout(axis)
        row.setContentsMargins(0, 0, 0, 0)
        for c in "xyz":
            # a direction: any length, as the property editor and make_vibration take it (a
            # range of -1..1 clamped the other components of (2, 0, 1) when one was edited)
            spin = _dspin(-1e6, 1e6, 0.1, "", 3)
            spin.setMinimumWidth(SPIN_WIDTH_PX)
            self.vibration_widgets[f"Axis.{c}"] = spin
            row.addWidget(spin)
        for name, widget in self.vibration_widgets.items():
            widget.setObjectName(f"Vibration{name}")
            if isinstance(widget, QtWidgets.QCheckBox):
                widget.toggled.connect(lambda on: self.set_vibration("Powered", bool(on)))
            elif name.startswith("Axis."):
                widget.valueChanged.connect(lambda _v, c=name[-1]: self.set_vibration_axis(c))
            else:
                widget.valueChanged.connect(lambda v, n=name: self.set_vibration(n, float(v)))
        form.addRow("Frequency", self.vibration_widgets["Frequency"])
        form.addRow("Amplitude", self.vibration_widgets["Amplitude"])
        form.addRow("Axis", axis)
        form.addRow("Powered", self.vibration_widgets["Powered"])
        self.vibration_box = box
        return box

    # --- object -> widgets -------------------------------------------------------------

    def load(self):
        """Shows the object's current values (signals blocked: no echo back)."""
        self._loading = True
        try:
            self._load()
        finally:
            self._loading = False
        self.validate()

    def _load(self):
        obj = self.obj
        # a circular centre whose part moved in its App::Part (no recompute since) is
        # shown, and edited, where the part took it
        surface_object.follow_pattern_anchor(obj)
        self.name_label.setText(f"<b>{html.escape(obj.Label)}</b>")
        self._load_faces()
        names = obj.getEnumerationsOfProperty("Material")
        combo = self.widgets["Material"]
        if [combo.itemText(i) for i in range(combo.count())] != names:
            combo.clear()
            combo.addItems(names)
        for name, widget in self.widgets.items():
            prop, _, axis = name.partition(".")
            value = getattr(obj, prop)
            if axis:
                value = getattr(value, axis)
            if name == "RoughnessCategory":
                _set_widget(widget, int(value) - 1, index=True)
            elif isinstance(widget, QtWidgets.QComboBox):
                _set_widget(widget, str(value))
            else:
                _set_widget(widget, float(value) if hasattr(value, "Value") else value)
        for name, (label, field) in self.rows.items():
            shown = RELEVANT.get(name, lambda o: True)(obj)
            label.setVisible(shown)
            field.setVisible(shown)
        self._load_material_info()
        row = _core.roughness_category(int(obj.RoughnessCategory))
        # the balls are rendered far taller than the category's Ra: say both, so neither is mistaken for the other
        felt = (f"felt {float(obj.RoughnessHeight) * row.grid_size_mm * 1e3:.3g} µm high" if obj.FeelRoughness
                else "not felt")
        self.roughness_info.setText(f"Grid of {row.grid_size_mm:g} mm balls, {felt} "
                                    f"(the category's real surfaces: {ra_band(row)})")
        curve = obj.PatternCurve
        self.curve_label.setText("none: select a sketch or edges" if curve is None else
                                 f"{curve[0].Label}" + (f": {', '.join(curve[1])}" if curve[1] and any(curve[1])
                                                        else " (all edges)"))
        self._load_vibration()

    def _load_faces(self):
        status = {(o, f): s for o, f, s in surface_object.reference_status(self.obj)}
        wanted = [(f"{o.Name}.{f}", status.get((o.Name, f), "ok")) for o, f in surface_object.reference_pairs(self.obj)]
        current = [(self.faces.item(i).data(QtCore.Qt.UserRole), self.faces.item(i).data(QtCore.Qt.UserRole + 1))
                   for i in range(self.faces.count())]
        if current == wanted:
            return
        self.faces.blockSignals(True)
        self.faces.clear()
        for name, state in wanted:
            label = self.doc.getObject(name.split(".")[0]).Label
            item = QtWidgets.QListWidgetItem(f"{label}.{face_references.shown_face(name.split('.', 1)[1])}" +
                                             ("" if state == "ok" else f"  ({state})"))
            item.setData(QtCore.Qt.UserRole, name)
            item.setData(QtCore.Qt.UserRole + 1, state)
            if state == face_references.BROKEN:
                item.setIcon(QtGui.QIcon(icon("HaptiCAD_SurfaceBroken")))
                item.setForeground(QtGui.QBrush(QtGui.QColor(180, 0, 0)))
                item.setToolTip("The model changed and this face cannot be found unambiguously: select it "
                                "here, press Add and click the face in the 3D view to put it in its place")
            elif state == face_references.REMATCHED:
                item.setToolTip("FreeCAD renamed this face after a model edit; the tag followed it")
            self.faces.addItem(item)
        self.faces.blockSignals(False)
        self.add_button.blockSignals(True)
        self.add_button.setChecked(self.mode == "faces")
        self.add_button.blockSignals(False)

    def _load_material_info(self):
        obj = self.obj
        database = materials.default_database()
        known = obj.Material in database
        self.reset_material.setEnabled(known)
        self.reset_material.setToolTip("" if known else f"{obj.Material} is not in this machine's material "
                                       "database (a card of the colleague who made the document?): the "
                                       "values below stay as the document has them")
        unread = ""
        if database.errors:  # the designer's own materials missing from the list, said why
            more = len(database.errors) - 1
            unread = (f"<br><span style='color:#b00000'>Not read from your material files: "
                      f"{html.escape(database.errors[0])}" + (f" (and {more} more, in the Report view)" if more else "")
                      + "</span>")
        if not known:
            self.material_info.setText(f"{html.escape(obj.Material)} is not in the material database on this "
                                       "machine; the values below are the document's." + unread)
            return
        m = database.get(obj.Material)
        overridden = (abs(m.static_friction - obj.StaticFriction) > 1e-9 or
                      abs(m.dynamic_friction - obj.DynamicFriction) > 1e-9 or
                      abs(m.stiffness_n_per_mm - obj.Stiffness) > 1e-9)
        self.material_info.setText(
            f"Database: μs {m.static_friction:g}, μd {m.dynamic_friction:g} "
            f"(plausible {m.friction_min:g}–{m.friction_max:g}), {m.stiffness_n_per_mm:g} N/mm"
            + ("; <b>overridden below</b>" if overridden else "") + unread)
        self.material_info.setToolTip(f"Friction: {m.friction_source}\nBulk: {m.bulk_source}")

    def vibration(self):
        part = self.part()
        return vibration_object.vibration_of(part) if part is not None else None

    def parts(self):
        """The parts this surface's faces belong to, each once, in the order tagged."""
        parts = []
        for obj, _ in surface_object.reference_pairs(self.obj):
            if is_alive(obj) and obj not in parts:
                parts.append(obj)
        return parts

    def part(self):
        """The part chosen in the Vibration box (the first, until another is chosen)."""
        parts = self.parts()
        chosen = self.vibration_part.currentData()
        return next((p for p in parts if p.Name == chosen), parts[0] if parts else None)

    def _load_vibration(self):
        part = self.part()
        combo = self.vibration_part
        combo.blockSignals(True)
        combo.clear()
        for p in self.parts():
            vibrates = vibration_object.vibration_of(p) is not None
            combo.addItem(f"{p.Label} (vibrates)" if vibrates else p.Label, p.Name)
        if part is None:
            combo.addItem("tag a face first", "")
        combo.setCurrentIndex(max(combo.findData(part.Name if part is not None else ""), 0))
        combo.setEnabled(combo.count() > 1)
        # greyed: why, where the pointer asks
        combo.setToolTip("The part whose vibration is shown below: one of the parts this surface's faces belong "
                         "to" if combo.count() > 1 else
                         f"This surface's faces are all on {part.Label}: the vibration below is {part.Label}'s"
                         if part is not None else "Tag a face first: a vibration belongs to a part")
        combo.blockSignals(False)
        vib = self.vibration()
        if vib is not None:  # its axis too, as the pattern's centre (_load)
            vibration_object.follow_axis_anchor(vib)
        self.vibrates.setEnabled(part is not None)
        _set_widget(self.vibrates, vib is not None)
        for name, widget in self.vibration_widgets.items():
            widget.setEnabled(vib is not None)
            if vib is None:
                continue
            prop, _, axis = name.partition(".")
            value = getattr(vib, prop)
            _set_widget(widget, getattr(value, axis) if axis else value)

    # --- widgets -> object -------------------------------------------------------------

    def set_property(self, name, value):
        if self._loading:
            return
        self._in_transaction()
        if name == "TexturePeriod":  # a fit's message names the period it was made at
            self.fit_info.setText("")
        try:
            setattr(self.obj, name, value)
        except Exception as exc:  # a value the property refuses: say so, keep the old one
            self.load()
            self.show_problems([f"{_label(name)}: {exc}"])
            return
        self.load()

    def set_vector(self, name, axis):
        """One component edited: only it changes (the others kept to the last digit, not
        as the boxes round them)."""
        if self._loading:
            return
        self._in_transaction()
        # the others where the part stands now: its App::Part may have moved since the load
        surface_object.follow_pattern_anchor(self.obj)
        self.set_property(name, _with_component(getattr(self.obj, name), axis,
                                                self.widgets[f"{name}.{axis}"].value()))

    def reset_to_material(self):
        database = materials.default_database()
        if self.obj.Material not in database:
            self.show_problems([f"{self.obj.Material} is not in the material database on this machine"])
            return
        m = database.get(self.obj.Material)
        self._in_transaction()
        self.obj.StaticFriction = m.static_friction
        self.obj.DynamicFriction = m.dynamic_friction
        self.obj.Stiffness = m.stiffness_n_per_mm
        self.load()

    def choose_recordings(self):
        paths, _ = QtWidgets.QFileDialog.getOpenFileNames(
            None, "Recordings to fit the texture to", "", "CSV recordings (*.csv);;All files (*)")
        if paths:
            self.fit_recordings(paths)

    def choose_plot(self):
        path, _ = QtWidgets.QFileDialog.getSaveFileName(None, "Save the fit's plot", "texture_fit.png",
                                                        "PNG pictures (*.png)")
        if path:
            self.save_plot(path)

    def save_plot(self, path):
        """Draws the last fit into ``path`` (PNG) and says where, or why not."""
        from ..texture_fit_plot import plot_fit

        try:
            with busy_cursor():
                plot_fit(path, self.fit_report)
        except (OSError, ValueError) as exc:
            said = html.escape(str(exc), quote=False)
            self.fit_info.setText(self.fit_info.text() + f"<br><span style='color:#b00000'>Not plotted: {said}</span>")
            return False
        self.fit_info.setText(self.fit_info.text() + f"<br>Plot saved to {html.escape(path, quote=False)}")
        return True

    def fit_recordings(self, paths):
        """Fits the texture to the CSV files in ``paths`` and sets it; on an error nothing changes
        and the panel says why."""
        try:
            speeds = texture_fit.parse_speeds(self.fit_speeds.text())
        except ValueError as exc:
            said = html.escape(str(exc), quote=False)
            self.fit_info.setText(f"<span style='color:#b00000'>Recorded speeds: {said}</span>")
            return False
        try:
            with busy_cursor():  # reading long recordings takes seconds
                report = texture_fit.fit_files(paths, float(self.obj.TexturePeriod), speeds,
                                               **self.fit_option_values())
                self._in_transaction()
                notes = texture_fit.apply_to_surface(self.obj, report)
        except (ValueError, OSError) as exc:
            said = html.escape(str(exc), quote=False)  # a header such as "force <N>" is text
            self.fit_info.setText(f"<span style='color:#b00000'>Not fitted, nothing changed: {said}</span>")
            return False
        self.load()
        self.fit_report = report
        self.fit_plot.setEnabled(True)
        fit = report.fit
        done = ", ".join(f"{s.speed_mps * 1e3:.0f}" for s in fit.speeds)
        self.fit_info.setText(
            f"Fitted to {len(fit.sections)} sections at {done} mm/s from {len(paths)} recording"
            f"{'s' if len(paths) != 1 else ''} (period λ {self.obj.TexturePeriod:g} mm): f_DC + v f_vis = "
            f"{fit.dc_n.intercept:.3f} {'-' if fit.dc_n.slope < 0 else '+'} {abs(fit.dc_n.slope):.3f} v N, "
            f"β_h {fit.beta_h_n.intercept:.3f} N, α_h {fit.alpha_h.intercept:.2f} (v per 400 mm/s)."
            + self._fit_options_said()
            + "".join(f"<br>{html.escape(n, quote=False)}" for n in notes))
        return True

    def _fit_options_said(self):
        """The options that differ from the paper's, said with the fit they made."""
        from .. import texture_fit_options as options

        chosen = self.fit_option_values()
        tolerance, lowpass = chosen["tolerance_percent"], chosen["lowpass_hz"]
        harmonics, min_periods = chosen["harmonics"], chosen["min_periods"]
        said = []
        if tolerance != options.DEFAULT_TOLERANCE_PERCENT:
            said.append(f"speed tolerance {tolerance:g} %")
        if lowpass != options.DEFAULT_LOWPASS_HZ:
            said.append(f"low-pass {lowpass:g} Hz" if lowpass > 0 else "no low-pass")
        if harmonics != options.DEFAULT_HARMONICS:
            said.append(f"{harmonics} harmonics")
        if min_periods != options.DEFAULT_MIN_PERIODS:
            said.append(f"sections of {min_periods} periods or more")
        return f" With {', '.join(said)}." if said else ""

    def use_selected_curve(self):
        curve, why = selected_curve()
        if curve is None:
            self.show_problems([why or "select a sketch, or edges, for the curve pattern first"])
            return
        self._in_transaction()
        self.obj.PatternCurve = curve
        self.load()

    def set_vibrates(self, on):
        if self._loading:
            return
        part, vib = self.part(), self.vibration()
        self._in_transaction()
        if on and vib is None and part is not None:
            vibration_object.make_vibration(self.doc, part)
        elif not on and vib is not None:
            self.doc.removeObject(vib.Name)
        self.load()

    def set_vibration(self, name, value):
        vib = self.vibration()
        if self._loading or vib is None:
            return
        self._in_transaction()
        setattr(vib, name, value)
        self.load()

    def set_vibration_axis(self, component):
        vib = self.vibration()
        if self._loading or vib is None:
            return
        self._in_transaction()
        vibration_object.follow_axis_anchor(vib)  # the others where the part stands now, as set_vector
        axis = _with_component(vib.Axis, component, self.vibration_widgets[f"Axis.{component}"].value())
        vib.Axis = axis
        self.load()
        if axis.Length == 0:
            self.show_problems([vibration_object.ZERO_AXIS])

    # --- Undo and Redo while open ---------------------------------------------------------

    def _undone_or_redone(self):
        """FreeCAD's Undo (or Redo) of the document while the panel is open: it took the
        panel's transaction (Undo commits it and undoes it). Handled once FreeCAD is done."""
        QtCore.QTimer.singleShot(0, self._after_undo_redo)

    def _after_undo_redo(self):
        """Shows the surface as the Undo or Redo left it (the widgets showed the edits it
        took back), and marks the transaction taken: the next edit opens another, so Cancel
        reverts what is done after it and OK makes that one undo step. Not opened now: a new
        transaction would clear FreeCAD's Redo list. An Undo of the surface's creation
        deletes it, and FreeCAD closes the panel."""
        if self.undo_redo is None or getattr(self, "document_gone", False) or not is_alive(self.obj):
            return
        if not self.doc.HasPendingTransaction:
            self._transaction_taken = True
            # Cancel now has no transaction to abort: it must not clear what the Undo touched
            self.up_to_date = [o.Name for o in self.doc.Objects if "Touched" not in o.State]
        if self.other_edits is not None:  # the Undo took those with it: Cancel no longer would
            self.other_edits.forget()
        self.load()

    def _in_transaction(self):
        """Before an edit: a transaction again when an Undo or Redo took the panel's."""
        if self._transaction_taken and not self.doc.HasPendingTransaction:
            self.doc.openTransaction("Edit haptic surface")
            # Cancel purges these: as up to date as they are now, after the Undo
            self.up_to_date = [o.Name for o in self.doc.Objects if "Touched" not in o.State]
        self._transaction_taken = False

    # --- faces -------------------------------------------------------------------------

    def set_mode(self, mode):
        self.mode = mode
        self.add_button.blockSignals(True)
        self.add_button.setChecked(mode == "faces")
        self.add_button.blockSignals(False)
        self.hint.setText({"faces": "Click faces in the 3D view to add them.",
                           "centre": "Click the centre of the circles on the part in the 3D view."}
                          .get(mode, "Press Add, then click faces in the 3D view."))
        self.validate()

    def set_adding(self, on):
        self.set_mode("faces" if on else None)

    def picked(self, doc_name, obj_name, sub, point):
        """A click in the 3D view (from the selection observer): ``obj_name`` is the
        top-level object clicked, ``sub`` the path from it to the element."""
        if self.mode is None:
            return
        if doc_name != self.doc.Name:  # another document's view: said, not silently ignored
            other = App.getDocument(doc_name) if doc_name in App.listDocuments() else None
            self.show_problems([f"that click was in {face_picking.document_file(other) if other else doc_name}: "
                                f"{self.obj.Label} tags faces of {face_picking.document_file(self.doc)}; click in "
                                "its view"])
            return
        root = self.doc.getObject(obj_name)
        if root is None:
            return
        if self.mode == "centre":
            link = face_picking.link_on_path(root, sub)
            if link is not None:  # the point lies on the link's copy, away from the faces felt
                self.show_problems([face_picking.centre_refusal(link, [p.Label for p in self.parts()])])
                return
            self._in_transaction()
            self.obj.PatternCenter = App.Vector(*point)
            self.set_mode(None)
            self.load()
        elif self.mode == "faces" and face_picking.element(sub).startswith("Face"):
            obj, face, why = face_picking.picked_face(root, sub)
            if why:  # shown through a link: its original, elsewhere, would be tagged
                self.show_problems([why])
                return
            self.add_face(obj, face)

    def add_face(self, obj, face):
        obj, face = face_references.owner_face(obj, face)
        if obj == self.obj or surface_object.is_haptic_surface(obj) or not hasattr(obj, "Shape"):
            return
        pairs = surface_object.reference_pairs(self.obj)
        if (obj, face) in pairs:
            if (obj.Name, face, face_references.BROKEN) in surface_object.reference_status(self.obj):
                self._in_transaction()
                surface_object.resign_reference(self.obj, obj, face)  # "pick it again"
                self.load()
            return
        other = surface_object.surface_tagging(obj, face, besides=self.obj)
        if other is not None:
            self.show_problems([f"{obj.Label}.{face} is already tagged by {other.Label}: a face feels one way; "
                                "remove it there first"])
            return
        broken = self._broken_chosen(obj)
        if broken is not None:  # picked again for the broken reference chosen in the list: in its place
            pairs = [(obj, face) if pair == broken else pair for pair in pairs]
        else:
            pairs = pairs + [(obj, face)]
        self._in_transaction()
        self.obj.References = surface_object.link_sub_list(pairs)
        self.load()

    def _broken_chosen(self, part):
        """(part, its face name) of the one reference chosen in the list when it is a broken
        one of ``part`` (one stepped aside, "Face6~1", names no face to pick again), else None."""
        chosen = self.faces.selectedItems()
        if len(chosen) != 1:
            return None
        obj_name, face = chosen[0].data(QtCore.Qt.UserRole).split(".", 1)
        # as the surface holds it now, not as the list last showed it (an Undo, the console)
        broken = obj_name == part.Name and (obj_name, face, face_references.BROKEN) in \
            surface_object.reference_status(self.obj)
        return (part, face) if broken else None

    def remove_selected_faces(self):
        chosen = {item.data(QtCore.Qt.UserRole) for item in self.faces.selectedItems()}
        if not chosen:
            self.show_problems(["select the faces to remove in the list first"])
            return
        self._in_transaction()
        self.obj.References = surface_object.link_sub_list(
            (o, f) for o, f in surface_object.reference_pairs(self.obj) if f"{o.Name}.{f}" not in chosen)
        self.highlight([])
        self.load()

    def highlight_selected(self):
        names = [item.data(QtCore.Qt.UserRole) for item in self.faces.selectedItems()]
        self.highlight(names)

    def highlight(self, names):
        """Selects the named faces in the 3D view and outlines them over the overlay."""
        mode, self.mode = self.mode, None  # our own selection is not a pick
        try:
            Gui.Selection.clearSelection()
            for name in names:
                obj_name, face = name.split(".", 1)
                part = self.doc.getObject(obj_name)
                if part is not None and face_references.ASIDE not in face:  # a broken one stepped aside: no face
                    Gui.Selection.addSelection(part, face)
        finally:
            self.mode = mode
        proxy = getattr(self.obj.ViewObject, "Proxy", None) if self.obj.ViewObject else None
        if proxy is not None and hasattr(proxy, "set_highlight"):
            proxy.set_highlight(names)

    # --- validation --------------------------------------------------------------------

    def validate(self):
        problems = surface_object.validate(self.obj)
        vib = self.vibration()
        if vib is not None:
            problems += [f"vibration: {p}" for p in vibration_object.validate(vib)]
        self.show_problems(problems)
        return problems

    def show_problems(self, problems):
        self.problems = problems
        if problems:
            # escaped: a label such as "Lid <rev B>" is text, not markup
            self.status.setText("<span style='color:#b00000'>⚠ "
                                + "<br>⚠ ".join(html.escape(p, quote=False) for p in problems) + "</span>")
        else:
            n = len(surface_object.reference_pairs(self.obj))
            notes = surface_object.hidden_part_notes(self.obj) + surface_compile.friction_notes(self.obj)
            notes += surface_compile.texture_notes(self.obj) + surface_compile.curve_notes(self.obj)
            notes += surface_compile.curved_face_notes(self.obj)
            notes += similarity_study.unpooling_notes(self.doc, self.pooled_at_open)
            rate_hz = preferences.load().servo_rate_hz  # the servo rate Feel will run at
            notes += [n for n in [surface_object.rate_note(self.obj, rate_hz)] if n]
            vib = self.vibration()
            if vib is not None:
                notes += [n for n in [vibration_object.rate_note(vib, rate_hz)] if n]
            self.status.setText(f"<span style='color:#006000'>✓ {n} face{'s' if n != 1 else ''} tagged"
                                f"{': click more to add them' if self.mode == 'faces' else ''}</span>"
                                + "".join(f"<br><span style='color:#a06000'>Note: {html.escape(note, quote=False)}.</span>"
                                          for note in notes))

    # --- FreeCAD's task dialog -----------------------------------------------------------

    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel)

    def accept(self):
        if getattr(self, "document_gone", False):
            return True
        if self.validate():
            return False
        self._stop_picking()
        self.doc.recompute()
        self.doc.commitTransaction()
        self._leave_edit()
        return True

    def reject(self):
        if getattr(self, "document_gone", False):
            return True
        others = self.other_edits.describe() if self.other_edits is not None else ""
        if others and not self._undo_others_too(others):
            return False  # the panel stays open
        self._stop_picking()
        # abort before leaving edit mode: resetEdit commits any open transaction
        self.doc.abortTransaction()
        for name in self.up_to_date:
            obj = self.doc.getObject(name)
            if obj is not None and "Touched" in obj.State:
                obj.purgeTouched()
        self._leave_edit()
        if is_alive(self.obj):  # an edit, not a creation: show the restored values
            self.obj.ViewObject.Proxy.refresh()
        return True

    def _edits_itself(self, obj):
        """Whether the panel edits ``obj``: its surface, and the vibration of a part it tags
        (another part's vibration edited meanwhile is another's edit)."""
        if obj == self.obj:
            return True
        if not vibration_object.is_haptic_vibration(obj) or not is_alive(self.obj):
            return False
        return obj.Part is not None and obj.Part.Name in {p.Name for p in self.parts()}

    def _undo_others_too(self, others):
        """Asks whether Cancel may undo ``others`` (OtherEdits.describe) with the surface's edits."""
        box = QtWidgets.QMessageBox(QtWidgets.QMessageBox.Warning, "Cancel the surface's edits",
                                    f"While this panel was open you also {others}.\n\nCancel undoes everything "
                                    "done since the panel opened: those too.", parent=Gui.getMainWindow())
        box.setInformativeText("To keep them, keep editing and press OK (the surface's edits are kept too).")
        undo = box.addButton("Undo those too", QtWidgets.QMessageBox.DestructiveRole)
        keep = box.addButton("Keep editing", QtWidgets.QMessageBox.RejectRole)
        box.setDefaultButton(keep)
        box.exec_()
        return box.clickedButton() is undo

    def _stop_watching_others(self):
        if self.other_edits is not None:
            self.other_edits.remove()
            self.other_edits = None
        if self.undo_redo is not None:
            self.undo_redo.remove()
            self.undo_redo = None

    def _stop_picking(self):
        self._stop_watching_others()
        Gui.Selection.removeObserver(self.picker)
        if self.closing is not None:
            self.closing.remove()
            self.closing = None
        self.highlight([])
        Gui.Selection.clearSelection()

    def document_closing(self):
        """The document and the surface are going: nothing of them is touched any more."""
        self.closing = None
        self.document_gone = True
        self._stop_watching_others()
        Gui.Selection.removeObserver(self.picker)
        if Gui.Control.activeDialog():
            Gui.Control.closeDialog()

    def _leave_edit(self):
        gui_doc = Gui.getDocument(self.doc.Name)
        if gui_doc is not None and gui_doc.getInEdit() is not None:
            gui_doc.resetEdit()




def _set_widget(widget, value, index=False):
    """Sets a widget's value without emitting, and only if it differs (no cursor jumps)."""
    widget.blockSignals(True)
    try:
        if index:
            if widget.currentIndex() != value:
                widget.setCurrentIndex(value)
        elif isinstance(widget, QtWidgets.QComboBox):
            if widget.currentText() != value:
                widget.setCurrentIndex(max(widget.findText(value), 0))
        elif isinstance(widget, QtWidgets.QCheckBox):
            if widget.isChecked() != bool(value):
                widget.setChecked(bool(value))
        elif isinstance(widget, (QtWidgets.QSpinBox, QtWidgets.QDoubleSpinBox)):
            if abs(widget.value() - value) > 10 ** -(getattr(widget, "decimals", lambda: 0)() + 1):
                widget.setValue(value)
    finally:
        widget.blockSignals(False)


def _roughness_item(row):
    return f"{row.category}: {ra_band(row)}"
