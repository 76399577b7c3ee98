/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core.Surface: closest points on a triangle surface. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

typedef struct {
    PyObject_HEAD
    facet_surface *handle;
} surface_object;

static int surface_init(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    surface_object *self = (surface_object *)self_obj;
    static char *keywords[] = {"xyz", "triangles", "face_start", "face_vertices", NULL};
    PyObject *xyz, *tri = Py_None, *start = Py_None, *faces = Py_None;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|OOO:Surface", keywords, &xyz, &tri, &start,
                                     &faces))
        return -1;
    if (self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Surface is already initialised");
        return -1;
    }
    PyObject *module = PyType_GetModule(Py_TYPE(self_obj));
    facet_error error;
    facet_status status;
    if (tri != Py_None) {
        Py_buffer xv, tv;
        if (py_get_buffer(xyz, "xyz", 'd', 0, -1, &xv) < 0)
            return -1;
        if (py_get_buffer(tri, "triangles", 'i', 0, -1, &tv) < 0) {
            PyBuffer_Release(&xv);
            return -1;
        }
        const Py_ssize_t nv = xv.len / 24, nt = tv.len / 12;
        if (xv.len % 24 || tv.len % 12 || nv > INT32_MAX || nt > INT32_MAX) {
            PyErr_SetString(PyExc_ValueError,
                            "xyz must hold 3 values per vertex and triangles 3 per triangle");
            PyBuffer_Release(&xv);
            PyBuffer_Release(&tv);
            return -1;
        }
        Py_BEGIN_ALLOW_THREADS
        status = facet_surface_create((int32_t)nv, xv.buf, (int32_t)nt, tv.buf, &self->handle,
                                      &error);
        Py_END_ALLOW_THREADS
        PyBuffer_Release(&xv);
        PyBuffer_Release(&tv);
    } else {
        if (start == Py_None || faces == Py_None) {
            PyErr_SetString(PyExc_TypeError,
                            "Surface needs triangles, or face_start and face_vertices");
            return -1;
        }
        mesh_views m;
        if (py_get_mesh(xyz, start, faces, 0, &m) < 0)
            return -1;
        Py_BEGIN_ALLOW_THREADS
        status = facet_surface_create_from_mesh(&m.mesh, &self->handle, &error);
        Py_END_ALLOW_THREADS
        py_release_mesh(&m);
    }
    if (status < 0) {
        py_raise_status(py_state(module), status, &error);
        return -1;
    }
    return 0;
}

static void surface_dealloc(PyObject *self_obj)
{
    surface_object *self = (surface_object *)self_obj;
    PyTypeObject *type = Py_TYPE(self_obj);
    facet_surface_free(&self->handle);
    type->tp_free(self_obj);
    Py_DECREF(type);
}

static PyObject *surface_closest(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    surface_object *self = (surface_object *)self_obj;
    static char *keywords[] = {"query", "closest", "distance", "triangle", "normal", "threads",
                               NULL};
    PyObject *query, *outs[4] = {Py_None, Py_None, Py_None, Py_None};
    int threads = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O|OOOOi:closest", keywords, &query, &outs[0],
                                     &outs[1], &outs[2], &outs[3], &threads))
        return NULL;
    if (!self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Surface is not initialised");
        return NULL;
    }
    Py_buffer qv;
    if (py_get_buffer(query, "query", 'd', 0, -1, &qv) < 0)
        return NULL;
    if (qv.len % 24) {
        PyErr_SetString(PyExc_ValueError, "query must hold 3 values per point");
        PyBuffer_Release(&qv);
        return NULL;
    }
    const Py_ssize_t n = qv.len / 24;
    static const char *names[4] = {"closest", "distance", "triangle", "normal"};
    static const char codes[4] = {'d', 'd', 'i', 'd'};
    const Py_ssize_t sizes[4] = {3 * n, n, n, 3 * n};
    Py_buffer views[4];
    void *ptrs[4] = {NULL, NULL, NULL, NULL};
    int got = 0;
    for (; got < 4; ++got) {
        if (outs[got] == Py_None)
            continue;
        if (py_get_buffer(outs[got], names[got], codes[got], 1, sizes[got], &views[got]) < 0)
            break;
        ptrs[got] = views[got].buf;
    }
    PyObject *result = NULL;
    if (got == 4) {
        facet_error error;
        facet_status status;
        Py_BEGIN_ALLOW_THREADS
        status = facet_surface_closest(self->handle, n, qv.buf, threads, ptrs[0], ptrs[1],
                                       ptrs[2], ptrs[3], &error);
        Py_END_ALLOW_THREADS
        if (status < 0)
            py_raise_status(py_state(PyType_GetModule(Py_TYPE(self_obj))), status, &error);
        else
            result = Py_NewRef(Py_None);
    }
    for (int k = 0; k < got; ++k)
        if (ptrs[k])
            PyBuffer_Release(&views[k]);
    PyBuffer_Release(&qv);
    return result;
}

static PyObject *surface_triangle_faces(PyObject *self_obj, PyObject *out)
{
    surface_object *self = (surface_object *)self_obj;
    if (!self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Surface is not initialised");
        return NULL;
    }
    const int32_t nt = facet_surface_triangle_count(self->handle);
    Py_buffer v;
    if (py_get_buffer(out, "out", 'i', 1, nt, &v) < 0)
        return NULL;
    int32_t *p = v.buf;
    for (int32_t t = 0; t < nt; ++t)
        p[t] = facet_surface_face(self->handle, t);
    PyBuffer_Release(&v);
    Py_RETURN_NONE;
}

static PyObject *surface_get_n_triangles(PyObject *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(facet_surface_triangle_count(((surface_object *)self)->handle));
}

static PyMethodDef surface_methods[] = {
    {"closest", (PyCFunction)(void (*)(void))surface_closest, METH_VARARGS | METH_KEYWORDS,
     "closest(query, closest=None, distance=None, triangle=None, normal=None, threads=0)\n\n"
     "Closest points on the surface of the points query (float64, 3n), written into the\n"
     "given buffers (float64 3n, float64 n, int32 n, float64 3n). Releases the GIL."},
    {"triangle_faces", surface_triangle_faces, METH_O,
     "triangle_faces(out) -> None\n\nWrite the mesh face of each triangle (int32; -1 when\n"
     "the surface was made from triangles)."},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef surface_getset[] = {
    {"n_triangles", surface_get_n_triangles, NULL, "number of triangles", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyType_Slot surface_slots[] = {
    {Py_tp_doc, "Surface(xyz, triangles=None, face_start=None, face_vertices=None)\n\n"
                "A triangle surface for closest-point queries (an AABB tree). Give triangles\n"
                "(int32, 3 per triangle), or a polygon mesh's face_start and face_vertices."},
    {Py_tp_init, surface_init},
    {Py_tp_dealloc, surface_dealloc},
    {Py_tp_methods, surface_methods},
    {Py_tp_getset, surface_getset},
    {0, NULL}};

static PyType_Spec surface_spec = {"facet._core.Surface", sizeof(surface_object), 0,
                                   Py_TPFLAGS_DEFAULT, surface_slots};

const facet_surface *py_surface_handle(PyObject *module, PyObject *obj)
{
    PyObject *type = PyObject_GetAttrString(module, "Surface");
    if (!type)
        return NULL;
    const int is = PyObject_IsInstance(obj, type);
    Py_DECREF(type);
    if (is < 0)
        return NULL;
    if (!is || !((surface_object *)obj)->handle) {
        PyErr_SetString(PyExc_TypeError, "reference must be a facet._core.Surface or None");
        return NULL;
    }
    return ((surface_object *)obj)->handle;
}

int py_add_surface(PyObject *module)
{
    PyObject *type = PyType_FromModuleAndSpec(module, &surface_spec, NULL);
    if (!type)
        return -1;
    int r = PyModule_AddObjectRef(module, "Surface", type);
    Py_DECREF(type);
    return r;
}
