# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reports of a planarization or a mesh check, as plain JSON-able dicts.

The command line writes them with ``--report``; the workbench shows them in
its task panel. Every value is a str, int, float, bool, None, list or dict:
numpy scalars and arrays are converted, and a NaN or infinite number becomes
None (JSON has no NaN, and a report must never carry one).

Planarity figures follow :func:`facet.planarity`: ``*_abs`` is the largest
distance of a face's vertices from its best-fit plane in model units,
``*_rel`` the same divided by the face's mean edge length.
"""

import json
import math
import os

import numpy as np

from facet.io.files import write_text

__all__ = ["planarize_report", "check_report", "quality_figures", "json_safe", "write_json",
           "count_noun", "face_degrees", "first_names", "point_text", "length_text"]

#: Keys of ``mesh.info`` copied into reports (lists of keys are left out).
_INFO_KEYS = ("format", "header", "dtype", "item", "openings_skipped", "unused_vertices_dropped",
              "repeated_corners_merged", "repeated_corners_first")


def point_text(point, units=None):
    """A point in a message, "(512346.25, 5712360.5)": ten significant digits, so that a
    point of a georeferenced plan reads to the millimetre, where six gave
    "(512346, 5.71236e+06)", ten metres out; no "-0". Followed by `units` when given:
    "(5999, 3000) mm"."""
    text = "(" + ", ".join(f"{float(value) + 0.0:.10g}" for value in point) + ")"
    return f"{text} {units}" if units else text


def length_text(units=None):
    """``text(x, spec=".3g")``: a length for a message, followed by `units` (the model's
    unit, "mm") when given: "2.99 mm", or "2.99" in model units."""
    def text(x, spec=".3g"):
        return f"{x:{spec}} {units}" if units else f"{x:{spec}}"

    return text


def count_noun(number, noun, grouped=False):
    """'1 quad', '2 quads', '0 quads', '1 vertex', '2 vertices': a count in a message;
    ``grouped``: with thousands separators ('1,536 quads')."""
    shown = f"{number:,}" if grouped else f"{number}"
    if number == 1:
        return f"{shown} {noun}"
    return f"{shown} {'vertices' if noun == 'vertex' else noun + 's'}"


def first_names(names, limit):
    """The first ``limit`` of ``names`` joined by commas, with ", ..." when there are more:
    the parts or panels a message names ("P-R01C01, P-R01C02, ...")."""
    names = list(names)
    return ", ".join(names[:limit]) + (", ..." if len(names) > limit else "")


def _version():
    from facet import __version__

    return __version__


def _path(path):
    return None if path is None else os.fspath(path)


def face_degrees(mesh):
    """Number of faces of each degree, as {"3": n, "4": m, ...}."""
    degrees, counts = np.unique(mesh.degrees, return_counts=True)
    return {str(int(d)): int(c) for d, c in zip(degrees, counts)}


def degrees_text(face_degrees, grouped=False):
    """The faces by kind for a message, from :func:`face_degrees`: "20 pentagons, 76
    hexagons, 19 7-gons"; ``grouped``: the counts with thousands separators ("1,536
    quads")."""
    names = {"3": "triangle", "4": "quad", "5": "pentagon", "6": "hexagon"}
    ordered = sorted(face_degrees.items(), key=lambda item: int(item[0]))
    return ", ".join(count_noun(count, names.get(degree, degree + "-gon"), grouped)
                     for degree, count in ordered)


def _mean_edge_length(mesh):
    try:
        return mesh.mean_edge_length()
    except Exception:  # a mesh without edges: no length to report
        return None


def _source_facts(mesh):
    info = getattr(mesh, "info", None) or {}
    return {f"source_{key}": info[key] for key in _INFO_KEYS if key in info}


def _worst_face(per_face):
    values = np.asarray(per_face, dtype=np.float64)
    if values.size == 0 or not np.isfinite(values).any():
        return None
    return int(np.nanargmax(np.where(np.isfinite(values), values, -np.inf)))


def quality_figures(mesh, input=None, reference=None, threads=None):
    """The ``quality`` section of a report: :meth:`facet.QualityReport.as_dict`
    of `mesh` (a mesh or a PlanarizeResult) against `input`."""
    from facet.quality import quality

    return quality(mesh, input=input, reference=reference, threads=threads).as_dict()


def planarize_report(source, result, input_path=None, output_path=None, input_planarity=None):
    """Report of one planarization.

    Parameters
    ----------
    source : PolyMesh
        The mesh before planarization.
    result : PlanarizeResult
        What :func:`facet.planarize` returned for `source`.
    input_path, output_path : str or os.PathLike, optional
        Files read and written, recorded as given.
    input_planarity : PlanarityReport, optional
        Planarity of `source` if already measured; measured here otherwise.

    Returns
    -------
    dict
        Keys ``faces``, ``vertices``, ``iterations``, ``solve_seconds``,
        ``planarity_max_rel``, ``planarity_max_abs``, ``planarity_rms_rel``,
        ``displacement_rms``, ``displacement_max``, ``method``,
        ``stop_reason``, ``converged``, ``tol``, ``input_planarity_max_rel``,
        ``input_planarity_max_abs``, and more (``displacement_max_rel`` is
        ``displacement_max`` over the mean edge length of `source`;
        ``warnings`` lists what the solver noted about the mesh; ``quality``
        is :meth:`facet.QualityReport.as_dict` of the result against
        `source`: planarity, displacement, distance from the source's
        surface, smallest angles, edge ratio change, degenerate faces;
        ``quality_check``, ``narrow_corners``, ``quality_resolves`` and
        ``first_iterations`` say whether the solve re-solved a result with a
        new narrow corner, ``data_tangent`` the weight the result was solved
        with (larger than the options' when a re-solve held sliding vertices
        more firmly along the design), ``compared`` what method auto compared before it
        picked ``method``'s result, or None, ``stopped`` whether the solve was stopped
        after this result, before it had finished: see :class:`facet.PlanarizeResult`).
        Already JSON-safe.
    """
    if input_planarity is None:
        from facet import planarity

        input_planarity = planarity(source)
    after = result.planarity
    # before and after over the same faces: the exempt ones are in neither
    input_planarity = input_planarity.leaving_out(getattr(after, "exempt", None))
    options = dict(getattr(result, "options", None) or {})
    mean_edge = _mean_edge_length(source)
    displacement_max = float(result.displacement_max)
    report = {
        "command": "planarize",
        "facet_version": _version(),
        "input": _path(input_path),
        "output": _path(output_path),
        "faces": source.n_faces,
        "vertices": source.n_vertices,
        "face_degrees": face_degrees(source),
        "mean_edge_length": mean_edge,
        "method": result.method,
        "tol": options.get("tol", options.get("tol_rel")),
        "tol_abs": options.get("tol_abs"),
        "max_iter": options.get("max_iter"),
        "iterations_requested": options.get("iterations"),
        "iterations": int(result.iterations),
        "stop_reason": str(result.stop_reason),
        "converged": bool(result.converged),
        "quality_check": str(getattr(result, "quality_check", "not_checked")),
        "narrow_corners": int(getattr(result, "narrow_corners", 0)),
        "quality_resolves": int(getattr(result, "quality_resolves", 0)),
        "data_tangent": getattr(result, "data_tangent", None),
        "first_iterations": int(getattr(result, "first_iterations", result.iterations)),
        "threads": int(getattr(result, "threads", 0)),
        "compared": getattr(result, "compared", None),
        "stopped": bool(getattr(result, "stopped", False)),
        "quality_timed_out": bool(getattr(result, "quality_timed_out", False)),
        "solve_seconds": float(result.solve_seconds),
        "input_planarity_max_rel": input_planarity.max_rel_all,
        "input_planarity_max_abs": input_planarity.max_abs_all,
        "input_planarity_rms_rel": input_planarity.rms_rel_all,
        "planarity_max_rel": after.max_rel_all,
        "planarity_max_abs": after.max_abs_all,
        "planarity_rms_rel": after.rms_rel_all,
        "planarity_diagonal_max": after.diagonal_max,
        "worst_face": (after.worst_faces(1) or [None])[0] if after.n_exempt else
        _worst_face(after.max_rel),
        "exempt_faces": after.n_exempt,
        "displacement_rms": float(result.displacement_rms),
        "displacement_max": displacement_max,
        "displacement_max_rel": (
            displacement_max / mean_edge if mean_edge else None
        ),
        "options": options,
        "warnings": list(getattr(result, "warnings", None) or []),
        "quality": quality_figures(result, input=source),
        "data": getattr(result, "data", None),
    }
    if getattr(result, "reference_given", False) and result.reference is not None:
        # the design surface given: how far the panels are from it (the quality section's
        # distance is from the input mesh's own surface)
        from facet.quality import quality

        to_design = quality(result.mesh, reference=result.reference).as_dict()
        report["reference_distance_rms"] = to_design["distance_rms"]
        report["reference_distance_max"] = to_design["distance_max"]
    report.update(_source_facts(source))
    return json_safe(report)


def check_report(mesh, planarity_report, validation_report, path=None):
    """Report of a mesh check.

    Parameters
    ----------
    mesh : PolyMesh
    planarity_report : PlanarityReport
        :func:`facet.planarity` of `mesh`.
    validation_report : dict
        :meth:`PolyMesh.validate` of `mesh`.
    path : str or os.PathLike, optional
        The file checked, recorded as given.

    Returns
    -------
    dict
        Mesh size and shape (``faces``, ``vertices``, ``edges``,
        ``boundary_edges``, ``non_manifold_edges``, ``isolated_vertices``,
        ``duplicate_faces`` and ``first_duplicate_faces`` (faces with the vertices of
        another: :func:`facet.mesh.duplicate_faces`), ``coincident_vertex_pairs`` and
        ``first_coincident_vertices`` (vertices at one
        point that are not one vertex: :func:`facet.mesh.coincident_vertices`),
        ``opposite_windings`` and ``first_opposite_windings`` (edges between faces
        wound opposite ways, and the first such pair of faces:
        :func:`facet.mesh.opposite_windings`),
        ``max_degree``, ``face_degrees``, ``mean_edge_length``, ``bounds``),
        planarity (``planarity_max_rel``, ``planarity_max_abs``,
        ``planarity_rms_rel``, ``planarity_diagonal_max``, ``worst_face``),
        ``quality`` (face shape: smallest angle, degenerate faces; see
        :func:`facet.quality`) and what the reader noted (``source_*``).
        Already JSON-safe.
    """
    from facet.mesh import coincident_vertices, duplicate_faces, opposite_windings

    validation = dict(validation_report)
    coincident = coincident_vertices(mesh)
    duplicates = duplicate_faces(mesh)
    windings = opposite_windings(mesh)
    lower, upper = mesh.bounds()
    report = {
        "command": "check",
        "facet_version": _version(),
        "input": _path(path),
        "faces": mesh.n_faces,
        "vertices": mesh.n_vertices,
        "face_degrees": face_degrees(mesh),
        "edges": validation.get("n_edges"),
        "boundary_edges": validation.get("n_boundary_edges"),
        "non_manifold_edges": validation.get("n_non_manifold_edges"),
        "isolated_vertices": validation.get("n_isolated_vertices"),
        "first_non_manifold_edge": validation.get("first_non_manifold_edge"),
        "first_isolated_vertex": validation.get("first_isolated_vertex"),
        "duplicate_faces": duplicates[0],
        "first_duplicate_faces": duplicates[1],
        "coincident_vertex_pairs": coincident[0],
        "first_coincident_vertices": coincident[1],
        "opposite_windings": windings[0],
        "first_opposite_windings": windings[1],
        "max_degree": validation.get("max_degree"),
        "mean_edge_length": _mean_edge_length(mesh),
        "bounds": {"min": lower, "max": upper},
        "planarity_max_rel": planarity_report.max_rel_all,
        "planarity_max_abs": planarity_report.max_abs_all,
        "planarity_rms_rel": planarity_report.rms_rel_all,
        "planarity_diagonal_max": planarity_report.diagonal_max,
        "worst_face": _worst_face(planarity_report.max_rel),
        "quality": quality_figures(mesh),
    }
    report.update(_source_facts(mesh))
    return json_safe(report)


def json_safe(value):
    """Convert `value` into plain JSON types, non-finite numbers into None.

    Parameters
    ----------
    value : object
        Nested dicts, lists, tuples, numpy arrays and scalars, paths, numbers.

    Returns
    -------
    object
        The same structure with dict keys as str, tuples and arrays as lists,
        numpy scalars as Python numbers, paths as str and NaN/inf as None.
        Anything else becomes its ``str``.
    """
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        value = float(value)
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(key): json_safe(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(item) for item in value]
    if isinstance(value, np.ndarray):
        return json_safe(value.tolist())
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return str(value)


def write_json(report, path):
    """Write a report as indented JSON (never NaN: those become null).

    Parameters
    ----------
    report : dict
    path : str or os.PathLike
        Replaced if it exists; never left half-written.
    """
    text = json.dumps(json_safe(report), allow_nan=False, indent=2) + "\n"
    write_text(path, [text])
