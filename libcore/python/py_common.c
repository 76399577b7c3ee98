/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Helpers shared by the binding files of facet._core: module state, status
 * codes to exceptions, buffer views. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

#include <string.h>

module_state *py_state(PyObject *module)
{
    return (module_state *)PyModule_GetState(module);
}

const char *py_status_name(facet_status status)
{
    switch (status) {
#define NAME_CASE(name, value, text) \
    case name:                        \
        return #name;
        FACET_STATUS_LIST(NAME_CASE)
#undef NAME_CASE
    }
    return "FACET_UNKNOWN";
}

/* Sets obj.name = value and drops the reference to value. */
int py_set_attr(PyObject *obj, const char *name, PyObject *value)
{
    if (!value)
        return -1;
    int r = PyObject_SetAttrString(obj, name, value);
    Py_DECREF(value);
    return r;
}

/* Raises CoreError (or Cancelled, or MemoryError) for a failed call. */
PyObject *py_raise_status(module_state *st, facet_status status, const facet_error *error)
{
    if (status == FACET_ERROR_OUT_OF_MEMORY)
        return PyErr_NoMemory();
    PyObject *type = status == FACET_ERROR_CANCELLED ? st->cancelled : st->core_error;
    const char *message = error && error->message[0] ? error->message : facet_status_string(status);
    PyObject *value = PyObject_CallFunction(type, "s", message);
    if (!value)
        return NULL;
    if (py_set_attr(value, "status", PyLong_FromLong((long)status)) < 0 ||
        py_set_attr(value, "status_name", PyUnicode_FromString(py_status_name(status))) < 0 ||
        py_set_attr(value, "face", PyLong_FromLongLong(error ? error->face : -1)) < 0 ||
        py_set_attr(value, "vertex", PyLong_FromLongLong(error ? error->vertex : -1)) < 0) {
        Py_DECREF(value);
        return NULL;
    }
    PyErr_SetObject(type, value);
    Py_DECREF(value);
    return NULL;
}

/* ---- buffers ----------------------------------------------------------- */

static int py_format_is(const char *format, char code)
{
    if (!format)
        return code == 'B';
    if (format[0] == '@' || format[0] == '=' || format[0] == '<')
        ++format;
    return format[0] == code && format[1] == '\0';
}

/* Gets a C-contiguous buffer of doubles ('d') or int32 ('i'). expected < 0
 * means any length. Sets a TypeError/ValueError naming the argument. */
int py_get_buffer(PyObject *obj, const char *name, char code, int writable, Py_ssize_t expected,
                      Py_buffer *view)
{
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, view, flags) < 0) {
        PyErr_Format(PyExc_TypeError, "%s must be a C-contiguous%s buffer of %s", name,
                     writable ? " writable" : "", code == 'd' ? "float64" : "int32");
        return -1;
    }
    const Py_ssize_t itemsize = code == 'd' ? 8 : 4;
    if (!py_format_is(view->format, code) || view->itemsize != itemsize) {
        PyErr_Format(PyExc_TypeError, "%s must hold %s values, not format '%s'", name,
                     code == 'd' ? "float64" : "int32", view->format ? view->format : "B");
        PyBuffer_Release(view);
        return -1;
    }
    const Py_ssize_t n = view->len / itemsize;
    if (expected >= 0 && n != expected) {
        PyErr_Format(PyExc_ValueError, "%s has %zd values, %zd expected", name, n, expected);
        PyBuffer_Release(view);
        return -1;
    }
    return 0;
}


void py_release_mesh(mesh_views *m)
{
    if (m->have_xyz)
        PyBuffer_Release(&m->xyz);
    if (m->have_start)
        PyBuffer_Release(&m->start);
    if (m->have_faces)
        PyBuffer_Release(&m->faces);
    m->have_xyz = m->have_start = m->have_faces = 0;
}

/* xyz may be NULL (topology only, then n_vertices is given). */
int py_get_mesh(PyObject *xyz, PyObject *start, PyObject *faces, Py_ssize_t n_vertices,
                    mesh_views *m)
{
    memset(m, 0, sizeof *m);
    if (xyz) {
        if (py_get_buffer(xyz, "xyz", 'd', 0, -1, &m->xyz) < 0)
            return -1;
        m->have_xyz = 1;
        if ((m->xyz.len / 8) % 3 != 0) {
            PyErr_Format(PyExc_ValueError, "xyz has %zd values, not a multiple of 3", m->xyz.len / 8);
            goto fail;
        }
        n_vertices = m->xyz.len / 24;
    }
    if (py_get_buffer(start, "face_start", 'i', 0, -1, &m->start) < 0)
        goto fail;
    m->have_start = 1;
    const Py_ssize_t n_faces = m->start.len / 4 - 1;
    if (n_faces < 0) {
        PyErr_SetString(PyExc_ValueError, "face_start must have n_faces + 1 values");
        goto fail;
    }
    const int32_t *fs = m->start.buf;
    if (py_get_buffer(faces, "face_vertices", 'i', 0, -1, &m->faces) < 0)
        goto fail;
    m->have_faces = 1;
    if (n_faces > 0 && fs[n_faces] != m->faces.len / 4) {
        PyErr_Format(PyExc_ValueError, "face_start ends at %d but face_vertices has %zd values",
                     (int)fs[n_faces], m->faces.len / 4);
        goto fail;
    }
    if (n_vertices > INT32_MAX || n_faces > INT32_MAX) {
        PyErr_SetString(PyExc_ValueError, "mesh too large");
        goto fail;
    }
    m->mesh.n_vertices = (int32_t)n_vertices;
    m->mesh.n_faces = (int32_t)n_faces;
    m->mesh.xyz = xyz ? m->xyz.buf : NULL;
    m->mesh.face_start = fs;
    m->mesh.face_vertices = m->faces.buf;
    return 0;
fail:
    py_release_mesh(m);
    return -1;
}

int py_count_progress(void *user, int64_t done, int64_t total)
{
    py_count_progress_state *ps = user;
    PyGILState_STATE gil = PyGILState_Ensure();
    int cancel = 0;
    if (PyErr_CheckSignals() < 0) {
        cancel = 1;
    } else if (ps->callback) {
        cancel = py_callback_cancels(
            PyObject_CallFunction(ps->callback, "LL", (long long)done, (long long)total));
    }
    py_keep_exception(&ps->exc_type, &ps->exc_value, &ps->exc_tb);
    PyGILState_Release(gil);
    return cancel;
}

int py_callback_cancels(PyObject *result)
{
    if (!result)
        return 1;
    int cancel = PyObject_IsTrue(result) == 1;
    Py_DECREF(result);
    return cancel;
}

void py_keep_exception(PyObject **type, PyObject **value, PyObject **tb)
{
    if (PyErr_Occurred() && !*type)
        PyErr_Fetch(type, value, tb);
    PyErr_Clear();
}
