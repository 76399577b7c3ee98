# SPDX-License-Identifier: LGPL-2.1-or-later
"""Meshes saved by compas and the tools built on it (RhinoVAULT, compas_tno).

Three layouts are read:

- the old compas format: a top-level object with ``vertex`` and ``face``
  maps, defaults in ``dva``/``dfa``;
- compas 2 (and 1.x): ``{"dtype": "compas.datastructures/Mesh", "data": {...}}``
  (``"value"`` instead of ``"data"`` in 1.x) with ``vertex``/``face`` inside
  and defaults in ``default_vertex_attributes``/``default_face_attributes``;
- a RhinoVAULT session, whose ``scene`` holds several meshes (Pattern,
  FormDiagram, ThrustDiagram, ForceDiagram): the ThrustDiagram, the 3-D
  shell, is read unless another item is asked for by name.

Vertex records are ``{"x": .., "y": .., "z": .., other attributes}``; a
missing coordinate takes the default vertex attribute. Face records are lists
of vertex keys (ints or strings).

Faces whose attribute ``_is_loaded`` (or the older ``is_loaded``) is false
are openings of a vault, not panels: they are skipped and counted. Only
vertices used by a kept face become mesh vertices, in the order of their
keys; the others (construction points, vertices of openings only) are
dropped and counted. ``mesh.info`` keeps the compas key of each vertex and
face so results can be written back.
"""

import json

from facet.errors import MeshError
from facet.io.checks import build_mesh
from facet.io.files import PROGRESS_EVERY, _plain, read_text, reading_progress, split_lines

__all__ = ["read_compas_json", "PREFERRED_SCENE_ITEM"]

#: The scene item read from a RhinoVAULT session when none is named.
PREFERRED_SCENE_ITEM = "ThrustDiagram"

_OPENING_ATTRIBUTES = ("_is_loaded", "is_loaded")
_SUPPORT_ATTRIBUTES = ("is_support", "is_fixed")


def _mesh_data(node):
    """The object holding the ``vertex`` and ``face`` maps of `node`, or None."""
    if not isinstance(node, dict):
        return None
    if isinstance(node.get("vertex"), dict) and isinstance(node.get("face"), dict):
        return node
    for key in ("data", "value"):
        inner = node.get(key)
        if isinstance(inner, dict):
            if isinstance(inner.get("vertex"), dict) and isinstance(inner.get("face"), dict):
                return inner
    return None


def _label(node, data):
    name = node.get("name") if isinstance(node, dict) else None
    if not name:
        attributes = data.get("attributes")
        if isinstance(attributes, dict):
            name = attributes.get("name")
    if not name:
        dtype = node.get("dtype") if isinstance(node, dict) else None
        if isinstance(dtype, str):
            name = dtype.rsplit("/", 1)[-1]
    return str(name) if name else "mesh"


def _scene_items(document):
    """(label, dtype, data) of every mesh in a compas scene, in file order."""
    scene = document.get("scene") if isinstance(document, dict) else None
    if not isinstance(scene, dict):
        return []
    scene_data = scene.get("data", scene)
    items = scene_data.get("items") if isinstance(scene_data, dict) else None
    if not isinstance(items, list):
        return []
    found = []
    for node in items:
        data = _mesh_data(node)
        if data is not None:
            found.append((_label(node, data), node.get("dtype"), data))
    return found


def _dtype_tail(dtype):
    return dtype.rsplit("/", 1)[-1] if isinstance(dtype, str) else ""


def _choose_mesh(document, item, source):
    """Find the mesh data in a compas document; return (data, dtype, item label)."""
    data = _mesh_data(document)
    if data is not None and item is None:
        return data, document.get("dtype"), None
    candidates = _scene_items(document)
    if data is not None:
        candidates.insert(0, (_label(document, data), document.get("dtype"), data))
    if not candidates:
        raise MeshError(
            "no compas mesh found (expected 'vertex' and 'face' maps, "
            "a compas 2 'data' object or a scene with meshes)",
            source=source,
        )
    wanted = PREFERRED_SCENE_ITEM if item is None else item
    for label, dtype, data in candidates:
        if wanted.lower() in (label.lower(), _dtype_tail(dtype).lower()):
            return data, dtype, label
    if item is not None:
        names = ", ".join(label for label, _, _ in candidates)
        raise MeshError(f"no mesh named {item!r} in the file (found: {names})", source=source)
    label, dtype, data = candidates[0]
    return data, dtype, label


def _key(value):
    """Normalise a compas key (int or str) to the string used in JSON maps."""
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    text = str(value).strip()
    try:
        return str(_int(text))
    except ValueError:
        return text


def _keyed(records, what, source):
    """`records` by normalised key; two keys that name the same one ("1" and "01") are
    refused rather than one record silently replacing the other."""
    keyed, given = {}, {}
    for key, record in records.items():
        name = _key(key)
        if name in keyed:
            raise MeshError(f"{what} keys {given[name]!r} and {key!r} both name {what} "
                            f"{_shown_key(name)!r}", source=source)
        keyed[name], given[name] = record, key
    return keyed


def _int(key):
    """A key as an integer (ValueError when it is not one as JSON writes them: "1_0" is
    not 10)."""
    if not _plain(str(key)):
        raise ValueError(key)
    return int(key)


def _ordered_keys(keys):
    """Keys in numeric order when all are integers, else in file order."""
    keys = list(keys)
    try:
        return sorted(keys, key=_int)
    except ValueError:
        return keys


def _shown_key(key):
    try:
        return _int(key)
    except ValueError:
        return key


def _attribute(record, defaults, names):
    for name in names:
        if isinstance(record, dict) and name in record:
            return record[name]
    for name in names:
        if name in defaults:
            return defaults[name]
    return None


def _coordinate(record, defaults, axis, key, source):
    value = record.get(axis) if isinstance(record, dict) else None
    if value is None:
        value = defaults.get(axis)
    if value is None:
        raise MeshError(f"vertex key {key!r} has no {axis} coordinate", source=source)
    if isinstance(value, bool):
        raise MeshError(f"vertex key {key!r}: {axis} is {value}, not a number", source=source)
    try:
        if isinstance(value, str) and not _plain(value.strip()):
            raise ValueError  # ("1_000" and other scripts' digits, as the OBJ reader)
        number = float(value)
    except (TypeError, ValueError, OverflowError):
        raise MeshError(
            f"vertex key {key!r}: cannot read {str(value)[:40]!r} as a number", source=source
        ) from None
    return number


def read_compas_json(path, *, item=None, validate=True, progress=None):
    """Read a mesh saved by compas, RhinoVAULT or compas_tno.

    Parameters
    ----------
    path : str or os.PathLike
    item : str, optional
        For a file holding several meshes (a RhinoVAULT session), the name or
        dtype of the one to read (``"FormDiagram"``). Default: the
        ThrustDiagram, else the first mesh.
    validate : bool
        Check the mesh fully (:meth:`PolyMesh.validate`). Default True.
    progress : callable, optional
        ``progress(done, total)`` in face and vertex records, once the JSON is parsed
        (every :data:`facet.io.files.PROGRESS_EVERY`, and at the end); True cancels
        (:class:`facet.Cancelled`, "reading NAME cancelled").

    Returns
    -------
    PolyMesh
        ``info`` holds ``source``, ``format`` (``"compas-json"``), ``dtype``,
        ``item`` (the scene item read, or None), ``openings_skipped`` and
        ``opening_keys`` (faces not read because ``_is_loaded`` is false),
        ``unused_vertices_dropped``, ``vertex_keys`` and ``face_keys`` (the
        compas key of each mesh vertex and face) and ``support_vertices``
        (mesh indices of vertices marked ``is_support`` or ``is_fixed``).

    Raises
    ------
    MeshError
        Not JSON (with the line), no mesh in the file, a face naming a
        vertex key the file does not have, a missing coordinate, no panels,
        or what :meth:`PolyMesh.validate` finds (with the compas face key).
    OSError
        When the file cannot be read.
    """
    source = path
    # UTF-8 with or without a BOM (.NET tools), or UTF-16 with one (Windows "Unicode")
    text = "\n".join(split_lines(read_text(path)))
    if not text.strip():
        raise MeshError("file is empty", source=source)
    try:
        document = json.loads(text)
    except json.JSONDecodeError as exc:
        raise MeshError(
            f"not valid JSON: {exc.msg} (column {exc.colno})", source=source, line=exc.lineno
        ) from None
    except RecursionError:
        raise MeshError("not valid JSON: nested too deeply", source=source) from None

    data, dtype, label = _choose_mesh(document, item, source)
    vertex_defaults = data.get("default_vertex_attributes") or data.get("dva") or {}
    face_defaults = data.get("default_face_attributes") or data.get("dfa") or {}
    face_data = data.get("facedata") or {}
    if not isinstance(vertex_defaults, dict):
        vertex_defaults = {}
    if not isinstance(face_defaults, dict):
        face_defaults = {}
    if not isinstance(face_data, dict):
        face_data = {}

    vertex_records = _keyed(data["vertex"], "vertex", source)
    face_records = _keyed(data["face"], "face", source)
    face_data = _keyed(face_data, "facedata", source)

    kept_faces = []
    opening_keys = []
    report = reading_progress(progress, path)
    total = len(face_records) + len(vertex_records)
    for done, face_key in enumerate(_ordered_keys(face_records)):
        if done % PROGRESS_EVERY == 0:
            report(done, total)
        corners = face_records[face_key]
        loaded = _attribute(face_data.get(face_key), face_defaults, _OPENING_ATTRIBUTES)
        if loaded is False:
            opening_keys.append(face_key)
            continue
        if not isinstance(corners, list):
            raise MeshError(f"face key {face_key!r} is not a list of vertex keys", source=source)
        if len(corners) < 3:
            raise MeshError(
                f"face key {face_key!r} has {len(corners)} vertices (at least 3 needed)",
                source=source,
            )
        corner_keys = [_key(corner) for corner in corners]
        for corner in corner_keys:
            if corner not in vertex_records:
                raise MeshError(
                    f"face key {face_key!r} uses vertex key {corner!r}, which the file "
                    "does not define",
                    source=source,
                )
        kept_faces.append((face_key, corner_keys))

    if not kept_faces:
        if opening_keys:
            raise MeshError(
                f"no faces (all {len(opening_keys)} faces are openings)", source=source
            )
        raise MeshError("no faces", source=source)

    used = {corner for _, corners in kept_faces for corner in corners}
    vertex_keys = [key for key in _ordered_keys(vertex_records) if key in used]
    index_of = {key: index for index, key in enumerate(vertex_keys)}

    coordinates = []
    supports = []
    for index, key in enumerate(vertex_keys):
        if index % PROGRESS_EVERY == 0:
            report(len(face_records) + index, total)
        record = vertex_records[key]
        for axis in ("x", "y", "z"):
            coordinates.append(_coordinate(record, vertex_defaults, axis, key, source))
        if any(
            _attribute(record, vertex_defaults, (name,)) is True for name in _SUPPORT_ATTRIBUTES
        ):
            supports.append(index)

    face_start = [0]
    face_vertices = []
    for _, corners in kept_faces:
        face_vertices.extend(index_of[corner] for corner in corners)
        face_start.append(len(face_vertices))

    face_keys = [_shown_key(face_key) for face_key, _ in kept_faces]
    shown_vertex_keys = [_shown_key(key) for key in vertex_keys]
    info = {
        "format": "compas-json",
        "dtype": dtype,
        "item": label,
        "openings_skipped": len(opening_keys),
        "opening_keys": [_shown_key(key) for key in opening_keys],
        "unused_vertices_dropped": len(vertex_records) - len(vertex_keys),
        "vertex_keys": shown_vertex_keys,
        "face_keys": face_keys,
        "support_vertices": supports,
    }
    report(total, total)
    return build_mesh(
        coordinates,
        face_start,
        face_vertices,
        source=source,
        info=info,
        face_names=face_keys,
        vertex_names=shown_vertex_keys,
        validate=validate,
    )
