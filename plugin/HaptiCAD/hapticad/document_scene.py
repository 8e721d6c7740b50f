# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the haptic scene of a FreeCAD document.

Every object that a HapticSurface references is tessellated whole (all its faces are
in the scene, tagged or not) with ``MeshPart.meshFromShape(..., Segments=True)``, which
gives a conforming mesh and one segment per B-rep face. CAD face ids are numbered
across objects in document order; ``face_names[id]`` is "Object.FaceN". Lengths in the
document are mm; the core gets metres through ``metres_per_unit = 1e-3``. No GUI.
"""
from dataclasses import dataclass, field

import numpy as np

import FreeCAD as App
import MeshPart

from . import _core
from .surface_compile import compile_surface, compile_vibration
from .surface_object import active_reference_pairs, surfaces_of
from .vibration_object import vibrations_of

MM = 1e-3  # metres per FreeCAD length unit


@dataclass(frozen=True)
class Tessellation:
    """How finely to tessellate: chord deviation (mm) and angle between normals (rad)."""

    linear_deflection_mm: float = 0.1
    angular_deflection_rad: float = 0.26


@dataclass
class DocumentScene:
    scene: object  # _core.HapticScene
    surfaces: object  # _core.SurfaceTable
    face_names: list  # CAD face id -> "Object.FaceN"
    face_surface: dict  # "Object.FaceN" -> name of the HapticSurface tagging it
    face_material: dict  # "Object.FaceN" -> material name
    shapes: dict = field(default_factory=dict)  # object name -> shape, global placement

    def face_id(self, name):
        try:
            return self.face_names.index(name)
        except ValueError:
            raise KeyError(f"{name} is not a face of the scene") from None

    def face_shape(self, name):
        """The B-rep face "Object.FaceN", in global coordinates."""
        obj_name, sub = name.split(".", 1)
        return self.shapes[obj_name].getElement(sub)

    def surface_properties(self, face_id):
        return self.surfaces.surface(face_id)


def global_shape(obj):
    """obj's shape placed where it sits in the document (App::Part parents included)."""
    shape = obj.Shape.copy()
    shape.Placement = obj.getGlobalPlacement()
    return shape


def tessellate(shape, settings):
    """(vertices #Vx3 mm, triangles #Tx3, face index #T) of a shape; face i is Face(i+1)."""
    mesh = MeshPart.meshFromShape(
        Shape=shape,
        LinearDeflection=settings.linear_deflection_mm,
        AngularDeflection=settings.angular_deflection_rad,
        Relative=False,
        Segments=True,
    )
    if mesh.countSegments() != len(shape.Faces):
        raise ValueError(
            f"tessellation gave {mesh.countSegments()} segments for {len(shape.Faces)} faces"
        )
    points, facets = mesh.Topology
    vertices = np.array([(p.x, p.y, p.z) for p in points], dtype=float)
    triangles = np.array(facets, dtype=np.int32).reshape(-1, 3)
    face_of = np.full(len(triangles), -1, dtype=np.int32)
    for i in range(mesh.countSegments()):
        face_of[list(mesh.getSegment(i))] = i
    if (face_of < 0).any():
        raise ValueError(f"{int((face_of < 0).sum())} triangles belong to no face")
    return vertices, triangles, face_of


def build_document_scene(doc, settings=Tessellation()):
    """The haptic scene of every HapticSurface and HapticVibration in ``doc``. Raises
    ValueError when there is nothing to feel, a face is tagged by two surfaces, or a
    surface's values cannot be compiled (the message names the surface)."""
    surfaces = surfaces_of(doc)
    vibrating = [v for v in vibrations_of(doc) if v.Part is not None]
    if not surfaces and not vibrating:
        raise ValueError(f"document {doc.Label} has no HapticSurface: tag faces first")
    tagged = {}  # "Object.FaceN" -> surface
    objects = []
    for surface in surfaces:
        # a broken reference names the wrong face (face_references): leave it out
        for obj, sub in active_reference_pairs(surface):
            name = f"{obj.Name}.{sub}"
            if name in tagged and tagged[name] is not surface:
                raise ValueError(f"{name} is tagged by both {tagged[name].Label} and {surface.Label}")
            tagged[name] = surface
            if obj not in objects:
                objects.append(obj)
    for vibration in vibrating:
        if vibration.Part not in objects:
            objects.append(vibration.Part)
    if not objects:
        raise ValueError(f"document {doc.Label}: every tagged face reference is broken; pick the faces again")

    all_vertices, all_triangles, all_faces, face_names = [], [], [], []
    shapes = {}
    offset = 0
    for obj in objects:
        shape = global_shape(obj)
        shapes[obj.Name] = shape
        try:
            vertices, triangles, face_of = tessellate(shape, settings)
        except ValueError as exc:
            raise ValueError(f"{obj.Label}: {exc}") from None
        for name in tagged:
            obj_name, sub = name.split(".", 1)
            if obj_name == obj.Name and int(sub[4:]) > len(shape.Faces):
                raise ValueError(f"{tagged[name].Label} references {name}, which no longer exists")
        all_vertices.append(vertices)
        all_triangles.append(triangles + offset)
        all_faces.append(face_of + len(face_names))
        face_names.extend(f"{obj.Name}.Face{i + 1}" for i in range(len(shape.Faces)))
        offset += len(vertices)

    table = [_core.SurfaceProperties() for _ in face_names]
    for name, surface in tagged.items():
        obj_name, sub = name.split(".", 1)
        table[face_names.index(name)] = compile_surface(surface, shapes[obj_name].getElement(sub))
    for index, vibration in enumerate(vibrating):
        prefix = vibration.Part.Name + "."
        for face_id, name in enumerate(face_names):
            if name.startswith(prefix):
                table[face_id].vibration = index
    scene = _core.HapticScene.build(
        np.vstack(all_vertices), np.vstack(all_triangles), np.concatenate(all_faces), MM
    )
    return DocumentScene(
        scene=scene,
        surfaces=_core.SurfaceTable(table, [compile_vibration(v) for v in vibrating]),
        face_names=face_names,
        face_surface={name: s.Name for name, s in tagged.items()},
        face_material={name: s.Material for name, s in tagged.items()},
        shapes=shapes,
    )
