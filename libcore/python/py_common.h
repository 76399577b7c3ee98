/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Shared by the binding files of facet._core.
 *
 * Each feature has its own binding file (py_planarize.c, ...) that defines
 * one registration function, int py_add_<feature>(PyObject *module), called
 * from core_exec in core_module.c. A binding file adds its functions with
 * PyModule_AddFunctions and its heap types with PyType_FromModuleAndSpec; a
 * method of such a type finds the module (and so CoreError) through
 * PyType_GetModule(Py_TYPE(self)). */
#ifndef FACET_PY_COMMON_H
#define FACET_PY_COMMON_H

#include <Python.h>

#include "facet.h"

typedef struct {
    PyObject *core_error;
    PyObject *cancelled;
} module_state;

module_state *py_state(PyObject *module);

/* "FACET_ERROR_REPEATED_VERTEX" */
const char *py_status_name(facet_status status);

/* Sets obj.name = value and drops the reference to value (which may be NULL:
 * then returns -1 with the error already set). */
int py_set_attr(PyObject *obj, const char *name, PyObject *value);

/* Raises CoreError (or Cancelled, or MemoryError) for a failed call; returns
 * NULL. error may be NULL. */
PyObject *py_raise_status(module_state *st, facet_status status, const facet_error *error);

/* A facet_count_progress_fn calling a Python callable (may be NULL) with (done, total),
 * run with the GIL released: it takes the GIL for the call and for Ctrl+C (both cancel:
 * a true result, an exception, a signal). An exception is kept in exc_* for the caller to
 * restore once the library returns. */
typedef struct {
    PyObject *callback;
    PyObject *exc_type, *exc_value, *exc_tb;
} py_count_progress_state;
int py_count_progress(void *user, int64_t done, int64_t total);

/* A progress callback's result (a new reference, or NULL when it raised; released
 * here): 1, cancel, when it raised or returned something true. */
int py_callback_cancels(PyObject *result);

/* Under a trampoline, with the GIL: keeps the first exception raised in *type, *value,
 * *tb (for the caller to restore once the library returns) and clears the error. */
void py_keep_exception(PyObject **type, PyObject **value, PyObject **tb);

/* Gets a C-contiguous buffer of doubles ('d') or int32 ('i'). expected < 0
 * means any length. Sets a TypeError/ValueError naming the argument and
 * returns -1 on failure. */
int py_get_buffer(PyObject *obj, const char *name, char code, int writable, Py_ssize_t expected,
                  Py_buffer *view);

typedef struct {
    Py_buffer xyz, start, faces;
    int have_xyz, have_start, have_faces;
    facet_mesh mesh;
} mesh_views;

/* Views a mesh given as xyz (float64, 3n; may be NULL for topology only,
 * then n_vertices is used), face_start and face_vertices (int32). */
int py_get_mesh(PyObject *xyz, PyObject *start, PyObject *faces, Py_ssize_t n_vertices,
                mesh_views *m);
void py_release_mesh(mesh_views *m);

/* The C handle of a facet._core.Surface (py_surface.c); NULL with TypeError
 * set when obj is not one. */
const facet_surface *py_surface_handle(PyObject *module, PyObject *obj);

/* Registration functions of the binding files. */
int py_add_planarize(PyObject *module);
int py_add_surface(PyObject *module);
int py_add_quality(PyObject *module);
int py_add_cleanup(PyObject *module);
int py_add_lift(PyObject *module);
int py_add_panel(PyObject *module);

#endif
