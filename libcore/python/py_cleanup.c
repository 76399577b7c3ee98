/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core.cleanup: collapse short edges. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

#include <stdlib.h>

static PyObject *bytes_of(const void *data, Py_ssize_t size)
{
    return PyBytes_FromStringAndSize((const char *)data, size);
}

static PyObject *core_cleanup(PyObject *module, PyObject *args, PyObject *kwargs)
{
    static char *keywords[] = {"xyz", "face_start", "face_vertices", "min_edge", "relative",
                               NULL};
    PyObject *xyz, *start, *faces;
    double min_edge;
    int relative = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOOd|p:cleanup", keywords, &xyz, &start,
                                     &faces, &min_edge, &relative))
        return NULL;
    mesh_views m;
    if (py_get_mesh(xyz, start, faces, 0, &m) < 0)
        return NULL;
    const size_t nv = (size_t)(m.mesh.n_vertices > 0 ? m.mesh.n_vertices : 1);
    const size_t nf = (size_t)(m.mesh.n_faces > 0 ? m.mesh.n_faces : 1);
    const size_t nc = (size_t)(m.faces.len / 4 > 0 ? m.faces.len / 4 : 1);
    double *xyz_out = malloc(sizeof(double) * 3 * nv);
    int32_t *start_out = malloc(sizeof(int32_t) * (nf + 1));
    int32_t *fv_out = malloc(sizeof(int32_t) * nc);
    int32_t *map = malloc(sizeof(int32_t) * nv);
    int32_t *collapsed = malloc(sizeof(int32_t) * 2 * nv);
    int32_t *removed = malloc(sizeof(int32_t) * nf);
    PyObject *result = NULL;
    if (!xyz_out || !start_out || !fv_out || !map || !collapsed || !removed) {
        PyErr_NoMemory();
        goto done;
    }
    facet_cleanup_options options = {min_edge, relative};
    facet_cleanup_result r;
    facet_error error;
    facet_status status;
    Py_BEGIN_ALLOW_THREADS
    status = facet_cleanup(&m.mesh, &options, xyz_out, start_out, fv_out, map, collapsed, removed,
                           &r, &error);
    Py_END_ALLOW_THREADS
    if (status < 0) {
        py_raise_status(py_state(module), status, &error);
        goto done;
    }
    result = Py_BuildValue(
        "{s:N,s:N,s:N,s:N,s:N,s:N,s:i,s:d,s:s}", "xyz", bytes_of(xyz_out, 24 * (Py_ssize_t)r.n_vertices),
        "face_start", bytes_of(start_out, 4 * ((Py_ssize_t)r.n_faces + 1)), "face_vertices",
        bytes_of(fv_out, 4 * (Py_ssize_t)r.n_corners), "vertex_map",
        bytes_of(map, 4 * (Py_ssize_t)m.mesh.n_vertices), "collapsed_edges",
        bytes_of(collapsed, 8 * (Py_ssize_t)r.n_collapsed), "removed_faces",
        bytes_of(removed, 4 * (Py_ssize_t)r.n_removed_faces), "skipped", (int)r.n_skipped,
        "threshold", r.threshold, "message", status > 0 ? error.message : "");
done:
    free(xyz_out);
    free(start_out);
    free(fv_out);
    free(map);
    free(collapsed);
    free(removed);
    py_release_mesh(&m);
    return result;
}

static PyMethodDef cleanup_methods[] = {
    {"cleanup", (PyCFunction)(void (*)(void))core_cleanup, METH_VARARGS | METH_KEYWORDS,
     "cleanup(xyz, face_start, face_vertices, min_edge, relative=False) -> dict\n\n"
     "Collapse edges shorter than min_edge (a fraction of the mean edge when relative).\n"
     "Returns bytes of float64/int32 arrays: xyz, face_start, face_vertices, vertex_map,\n"
     "collapsed_edges (pairs), removed_faces; and skipped, threshold, message."},
    {NULL, NULL, 0, NULL}};

int py_add_cleanup(PyObject *module)
{
    return PyModule_AddFunctions(module, cleanup_methods);
}
