/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core.face_shape: per-face shape measures of the quality report. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

static PyObject *core_face_shape(PyObject *module, PyObject *args, PyObject *kwargs)
{
    static char *keywords[] = {"xyz", "face_start", "face_vertices", "xyz_input", "min_angle",
                               "area", "ratio_change", "threads", NULL};
    PyObject *xyz, *start, *faces, *input = Py_None;
    PyObject *outs[3] = {Py_None, Py_None, Py_None};
    int threads = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOO|OOOOi:face_shape", keywords, &xyz, &start,
                                     &faces, &input, &outs[0], &outs[1], &outs[2], &threads))
        return NULL;
    mesh_views m;
    if (py_get_mesh(xyz, start, faces, 0, &m) < 0)
        return NULL;
    Py_buffer in_view;
    int have_input = 0;
    if (input != Py_None) {
        if (py_get_buffer(input, "xyz_input", 'd', 0, 3 * (Py_ssize_t)m.mesh.n_vertices,
                          &in_view) < 0) {
            py_release_mesh(&m);
            return NULL;
        }
        have_input = 1;
    }
    static const char *names[3] = {"min_angle", "area", "ratio_change"};
    Py_buffer views[3];
    double *ptrs[3] = {NULL, NULL, NULL};
    int got = 0;
    for (; got < 3; ++got) {
        if (outs[got] == Py_None)
            continue;
        if (py_get_buffer(outs[got], names[got], 'd', 1, m.mesh.n_faces, &views[got]) < 0)
            break;
        ptrs[got] = views[got].buf;
    }
    PyObject *result = NULL;
    if (got == 3) {
        facet_error error;
        facet_status status;
        const double *xin = have_input ? in_view.buf : NULL;
        Py_BEGIN_ALLOW_THREADS
        status = facet_face_shape(&m.mesh, xin, threads, ptrs[0], ptrs[1], ptrs[2], &error);
        Py_END_ALLOW_THREADS
        if (status < 0)
            py_raise_status(py_state(module), status, &error);
        else
            result = Py_NewRef(Py_None);
    }
    for (int k = 0; k < got; ++k)
        if (ptrs[k])
            PyBuffer_Release(&views[k]);
    if (have_input)
        PyBuffer_Release(&in_view);
    py_release_mesh(&m);
    return result;
}

static PyMethodDef quality_methods[] = {
    {"face_shape", (PyCFunction)(void (*)(void))core_face_shape, METH_VARARGS | METH_KEYWORDS,
     "face_shape(xyz, face_start, face_vertices, xyz_input=None, min_angle=None, area=None,\n"
     "           ratio_change=None, threads=0) -> None\n\n"
     "Per-face smallest interior angle (radians), vector area and change of relative edge\n"
     "lengths against xyz_input, written into the given float64 buffers."},
    {NULL, NULL, 0, NULL}};

int py_add_quality(PyObject *module)
{
    return PyModule_AddFunctions(module, quality_methods);
}
