# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the haptic scene of a FreeCAD document.

Every object that a HapticSurface references is tessellated whole (all its faces are
in the scene, tagged or not) with ``MeshPart.meshFromShape(..., Segments=True)``, which
gives a conforming mesh and one segment per B-rep face, as finely as the accuracy
preset says (accuracy.py). Each triangle corner carries the exact normal of its B-rep
face there (``Face.normalAt``), for force shading. The core repairs the soup (welds
the faces' tessellations together, drops degenerate triangles) and reports what it
could not mend: ``DocumentScene.repair`` says it in one line. CAD face ids are numbered
across objects in document order; ``face_names[id]`` is "Object.FaceN". Lengths in the
document are mm; the core gets metres through ``metres_per_unit = 1e-3``. No GUI.
"""
from dataclasses import dataclass, field, replace

import numpy as np

import FreeCAD as App
import MeshPart

from . import _core
from . import accuracy as accuracy_presets
from . import tessellation_size
from .surface_compile import compile_surface, compile_vibration, global_shape, point_on_face  # noqa: F401 (re-exported)
from .surface_object import active_reference_pairs, deleted_parts, surfaces_of
from .vibration_object import faceless_note, vibrations_of

MM = 1e-3  # metres per FreeCAD length unit


class NeedsNewScene(ValueError):
    """An edit the scene being felt cannot take by recompiling its surfaces: it tags or
    shakes a part, or a face, the scene does not hold. Tessellating the document again
    (LiveSession.update_scene) takes it."""


@dataclass
class DocumentScene:
    scene: object  # _core.HapticScene
    surfaces: object  # _core.SurfaceTable
    face_names: list  # CAD face id -> "Object.FaceN"
    face_surface: dict  # "Object.FaceN" -> name of the HapticSurface tagging it
    face_material: dict  # "Object.FaceN" -> material name
    face_surface_label: dict = field(default_factory=dict)  # "Object.FaceN" -> the surface's Label, as shown
    shapes: dict = field(default_factory=dict)  # object name -> shape, global placement
    accuracy: object = None  # the accuracy.Accuracy it was built with
    repair: str = ""  # what the core's repair did and left undone, one line
    watertight: bool = True  # every edge between exactly two triangles after repair
    # "Object.FaceN" -> (its B-rep face in the scene's shapes, point_on_face of it): most
    # of what compiling a face costs, the same for every recompile on these shapes (a
    # property edit compiled the toothbrush's five faces in 3 ms, finding each again)
    face_points: dict = field(default_factory=dict)

    def contact_options(self):
        """The proxy's options for this scene: force shading as its accuracy says (on
        without one). Every renderer of the scene is made with them."""
        options = _core.ContactOptions()
        options.force_shading = self.accuracy is None or bool(self.accuracy.force_shading)
        return options

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


def tessellate(shape, accuracy):
    """(vertices #Vx3 mm, triangles #Tx3, face index #T, corner normals #Tx9) of a
    shape; face i is Face(i+1); corner normals are the B-rep face's exact normals.

    FreeCAD's meshes hold their points in single precision: a part placed 1 km from the
    origin came out on a 1/16 mm grid (a closed cylinder left with open edges, a 1 mm ball
    with a quarter of its triangles). So the shape is meshed about its own centre (a move
    of its placement, exact) and its points put back where it lies in doubles: rounded
    alike wherever the part is."""
    centre = shape.BoundBox.Center
    local = shape.copy()
    local.translate(-centre)
    mesh = MeshPart.meshFromShape(
        Shape=local,
        LinearDeflection=accuracy.linear_deflection_mm,
        AngularDeflection=accuracy.angular_deflection_rad,
        Relative=False,
        Segments=True,
    )
    if mesh.countSegments() != len(shape.Faces):
        raise ValueError(
            f"tessellation gave {mesh.countSegments()} segments for {len(shape.Faces)} faces"
        )
    points, facets = mesh.Topology
    vertices = np.array([(p.x, p.y, p.z) for p in points], dtype=float) + (centre.x, centre.y, centre.z)
    triangles = np.array(facets, dtype=np.int32).reshape(-1, 3)
    face_of = np.full(len(triangles), -1, dtype=np.int32)
    for i in range(mesh.countSegments()):
        face_of[list(mesh.getSegment(i))] = i
    if (face_of < 0).any():
        raise ValueError(f"{int((face_of < 0).sum())} triangles belong to no face")
    return vertices, triangles, face_of, corner_normals(shape, vertices, triangles, face_of)


def corner_normals(shape, vertices, triangles, face_of):
    """#Tx9: at each triangle corner, the unit normal of the triangle's B-rep face at
    that vertex (a vertex on an edge between faces gets each face's own normal). A
    plane's normal is computed once; a point the surface cannot parametrise falls back
    to the facet's own normal."""
    facet = np.cross(vertices[triangles[:, 1]] - vertices[triangles[:, 0]],
                     vertices[triangles[:, 2]] - vertices[triangles[:, 0]])
    length = np.linalg.norm(facet, axis=1, keepdims=True)
    facet = np.divide(facet, length, out=np.zeros_like(facet), where=length > 0)
    normals = np.repeat(facet, 3, axis=0).reshape(-1, 3, 3)
    order = np.argsort(face_of, kind="stable")
    bounds = np.searchsorted(face_of[order], np.arange(len(shape.Faces) + 1))
    for index, face in enumerate(shape.Faces):
        rows = order[bounds[index]:bounds[index + 1]]
        if len(rows) == 0:
            continue
        if face.Surface.TypeId == "Part::GeomPlane":
            n = _normal_at(face, face.CenterOfMass)
            if n is not None:
                normals[rows] = n
            continue
        # one B-rep evaluation per vertex of the face, shared by its triangles' corners
        corners = triangles[rows]
        unique, inverse = np.unique(corners, return_inverse=True)
        at = [_normal_at(face, App.Vector(*vertices[v])) for v in unique]
        known = np.array([n is not None for n in at])
        values = np.array([n if n is not None else (0.0, 0.0, 0.0) for n in at], dtype=float)
        inverse = inverse.reshape(corners.shape)
        use = known[inverse]
        block = normals[rows]
        block[use] = values[inverse][use]
        normals[rows] = block
    # the facet's winding and the face's normal agree on which side is out
    flip = np.einsum("tcj,tj->tc", normals, facet) < 0
    normals[flip] *= -1
    return normals.reshape(-1, 9)


def _normal_at(face, point):
    try:
        u, v = face.Surface.parameter(point)
        n = face.normalAt(u, v)
    except Exception:  # noqa: BLE001 (OCC raises its own kinds; the facet normal stands in)
        return None
    length = n.Length
    return (n.x / length, n.y / length, n.z / length) if length > 0 else None


def tagged_objects(doc):
    """The parts a Feel session on ``doc`` holds: tagged by a surface or vibrating.
    ValueError when nothing is tagged."""
    return _tagging(doc)[2]


def _tagging(doc):
    """({"Object.FaceN": surface}, [vibration], [tagged or vibrating object]) of doc."""
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
        # a model edit can leave a vibrating part without faces (make_vibration refuses one)
        if faceless_note(vibration.Part):
            raise ValueError(f"{vibration.Label}: {faceless_note(vibration.Part)}, or delete {vibration.Label}")
        if vibration.Part not in objects:
            objects.append(vibration.Part)
    return tagged, vibrating, objects


def _surface_table(tagged, vibrating, face_names, shapes, face_points):
    """The SurfaceTable of the scene's faces: each tagged face's compiled surface, the
    vibration of each vibrating part's faces, plain properties elsewhere.
    ``face_points``: the scene's DocumentScene.face_points, read and filled."""
    table = [_core.SurfaceProperties() for _ in face_names]
    for name, surface in tagged.items():
        if name not in face_points:
            obj_name, sub = name.split(".", 1)
            face = shapes[obj_name].getElement(sub)
            face_points[name] = (face, point_on_face(face))
        face, uv = face_points[name]
        table[face_names.index(name)] = compile_surface(surface, face, uv)
    for index, vibration in enumerate(vibrating):
        prefix = vibration.Part.Name + "."
        for face_id, name in enumerate(face_names):
            if name.startswith(prefix):
                table[face_id].vibration = index
    return _core.SurfaceTable(table, [compile_vibration(v) for v in vibrating])


def recompile_surfaces(doc, doc_scene):
    """doc_scene with its surfaces compiled again from doc's HapticSurfaces and
    HapticVibrations as they are now: what a property edit (material, friction,
    roughness, pattern, texture, vibration) or a retag among the scene's faces changes,
    without tessellating again. The scene itself is shared, not copied. Raises
    ValueError, naming the surface, when a value cannot be compiled, and NeedsNewScene
    (a ValueError) when the edit tags or shakes a part the scene does not hold, or
    leaves a part of the scene untagged (or deletes it)."""
    tagged, vibrating, objects = _tagging(doc)
    for obj in objects:
        if obj.Name not in doc_scene.shapes:
            raise NeedsNewScene(f"{obj.Label} is not in the scene being felt")
    gone = set(doc_scene.shapes) - {obj.Name for obj in objects}
    if gone:
        raise NeedsNewScene(f"{', '.join(sorted(gone))} no longer tagged or gone from the document")
    for name, surface in tagged.items():
        if name not in doc_scene.face_names:
            raise NeedsNewScene(f"{surface.Label} references {name}, which the scene being felt does not have")
    return replace(
        doc_scene,
        surfaces=_surface_table(tagged, vibrating, doc_scene.face_names, doc_scene.shapes, doc_scene.face_points),
        face_surface={name: s.Name for name, s in tagged.items()},
        face_material={name: s.Material for name, s in tagged.items()},
        face_surface_label={name: s.Label for name, s in tagged.items()},
    )


def _nothing_tagged(doc):
    """Why no face of doc can be felt though it has surfaces: their parts were deleted,
    they tag no face, or every face reference broke."""
    surfaces = surfaces_of(doc)
    if any(s.References for s in surfaces):
        return f"document {doc.Label}: every tagged face reference is broken; pick the faces again"
    deleted = sorted({label for s in surfaces for label in deleted_parts(s)})
    if deleted:
        return (f"document {doc.Label}: the tagged part{'s' if len(deleted) > 1 else ''} "
                f"{', '.join(deleted)} {'were' if len(deleted) > 1 else 'was'} deleted; undo the deletion or tag "
                "the faces of another part")
    return f"document {doc.Label}: no surface tags a face; pick faces for one"


def build_document_scene(doc, accuracy=None):
    """The haptic scene of every HapticSurface and HapticVibration in ``doc``, at the
    given accuracy.Accuracy (the default preset when None). Raises ValueError when there
    is nothing to feel, a face is tagged by two surfaces, or a surface's values cannot
    be compiled (the message names the surface), and, before anything is meshed,
    tessellation_size.TooManyTriangles (a ValueError) when the parts would make too many
    triangles at this accuracy (naming the part and the deflections that would fit)."""
    accuracy = accuracy or accuracy_presets.preset()
    tagged, vibrating, objects = _tagging(doc)
    if not objects:
        raise ValueError(_nothing_tagged(doc))

    shapes = {obj.Name: global_shape(obj) for obj in objects}
    # refused before anything is meshed: a 1 m ball at Fine took 19 s and 1.15 GB on the
    # GUI thread, a 1 mm one at 0.573 degrees 508 s (tessellation_size)
    tessellation_size.refuse_too_many([(obj.Label, shapes[obj.Name]) for obj in objects], accuracy)

    all_vertices, all_triangles, all_faces, all_normals, face_names = [], [], [], [], []
    offset = 0
    for obj in objects:
        shape = shapes[obj.Name]
        try:
            vertices, triangles, face_of, normals = tessellate(shape, accuracy)
        except ValueError as exc:
            raise ValueError(f"{obj.Label}: {exc}") from None
        for name in tagged:
            obj_name, sub = name.split(".", 1)
            if obj_name == obj.Name and int(sub[4:]) > len(shape.Faces):
                raise ValueError(f"{tagged[name].Label} references {name}, which no longer exists")
        all_vertices.append(vertices)
        all_triangles.append(triangles + offset)
        all_faces.append(face_of + len(face_names))
        all_normals.append(normals)
        face_names.extend(f"{obj.Name}.Face{i + 1}" for i in range(len(shape.Faces)))
        offset += len(vertices)

    face_points = {}
    surface_table = _surface_table(tagged, vibrating, face_names, shapes, face_points)
    scene = _core.HapticScene.build(
        np.vstack(all_vertices), np.vstack(all_triangles), np.concatenate(all_faces), MM,
        corner_normals=np.vstack(all_normals), refine_edge=accuracy.refine_edge_mm,
    )
    report = scene.repair_report
    return DocumentScene(
        scene=scene,
        surfaces=surface_table,
        face_names=face_names,
        face_surface={name: s.Name for name, s in tagged.items()},
        face_material={name: s.Material for name, s in tagged.items()},
        face_surface_label={name: s.Label for name, s in tagged.items()},
        shapes=shapes,
        accuracy=accuracy,
        repair=report.describe(),
        watertight=report.watertight,
        face_points=face_points,
    )
