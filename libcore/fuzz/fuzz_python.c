/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * fuzz_python.c -- a libFuzzer target that embeds CPython and runs Facet's
 * Python readers (OBJ, OFF, compas JSON, plan drawings in DXF/CSV/mesh form,
 * CSV targets) on the fuzz bytes through tools/fuzz/harness.py, which also
 * hands what was read on to the compiled core.
 *
 * Coverage: libFuzzer sees the C code it was compiled with, not Python
 * lines. A C-level trace function (PyEval_SetTrace) hashes each executed
 * Python line with the previous one (AFL-style edges) into libFuzzer's
 * "extra counters" section, so the fuzzer is guided by Python line
 * coverage too.
 *
 * A finding is any exception other than facet.errors.InputError (the
 * harness decides; see its docstring): printed with its traceback, then
 * abort().
 *
 * Environment: FACET_FUZZ_WORKBENCH (the workbench/ directory),
 * FACET_FUZZ_HARNESS (tools/fuzz/), FACET_FUZZ_CORE (a directory holding a
 * sanitizer build of facet._core to use instead of the one in workbench/).
 * Defaults are compiled in from the source tree.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <frameobject.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef FACET_SOURCE_DIR
#define FACET_SOURCE_DIR "."
#endif
#ifndef FACET_CORE_DIR
#define FACET_CORE_DIR ""
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed);
size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max_size);

#define N_COUNTERS (1u << 16)
__attribute__((section("__libfuzzer_extra_counters"), used)) static uint8_t counters[N_COUNTERS];
static uint32_t previous;
static PyObject *one_input;

static int trace(PyObject *obj, PyFrameObject *frame, int what, PyObject *arg)
{
    (void)obj;
    (void)arg;
    if (what != PyTrace_LINE && what != PyTrace_CALL) return 0;
    PyCodeObject *code = PyFrame_GetCode(frame);
    uint64_t h = (uint64_t)(uintptr_t)code * 0x9E3779B97F4A7C15ull;
    Py_DECREF(code);
    h ^= (uint64_t)PyFrame_GetLineNumber(frame) * 0xC2B2AE3D27D4EB4Full;
    uint32_t here = (uint32_t)(h >> 32) ^ (uint32_t)h;
    uint8_t *c = &counters[(here ^ previous) % N_COUNTERS];
    if (*c < 255) ++*c;
    previous = here >> 1;
    return 0;
}

static const char *env_or(const char *name, const char *fallback)
{
    const char *v = getenv(name);
    return v && *v ? v : fallback;
}

static void fail_python(const char *what)
{
    fprintf(stderr, "fuzz_python: %s\n", what);
    if (PyErr_Occurred()) PyErr_Print();
    abort();
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *workbench = env_or("FACET_FUZZ_WORKBENCH", FACET_SOURCE_DIR "/workbench");
    const char *harness = env_or("FACET_FUZZ_HARNESS", FACET_SOURCE_DIR "/tools/fuzz");
    const char *core = env_or("FACET_FUZZ_CORE", FACET_CORE_DIR);
    PyConfig config;
    PyConfig_InitPythonConfig(&config);
    config.install_signal_handlers = 0; /* libFuzzer owns SIGINT and friends */
    config.parse_argv = 0;
    PyStatus status = Py_InitializeFromConfig(&config);
    PyConfig_Clear(&config);
    if (PyStatus_Exception(status)) {
        fprintf(stderr, "fuzz_python: cannot start Python: %s\n", status.err_msg ? status.err_msg : "?");
        abort();
    }
    /* sys.path: the harness and the workbench; a sanitizer-built facet._core
     * (FACET_FUZZ_CORE) is found first through facet.__path__. */
    PyObject *globals = PyDict_New();
    PyDict_SetItemString(globals, "__builtins__", PyEval_GetBuiltins());
    PyDict_SetItemString(globals, "workbench", PyUnicode_FromString(workbench));
    PyDict_SetItemString(globals, "harness_dir", PyUnicode_FromString(harness));
    PyDict_SetItemString(globals, "core_dir", PyUnicode_FromString(core));
    PyObject *r = PyRun_String(
        "import sys, importlib.machinery, importlib.util\n"
        "sys.path[:0] = [harness_dir, workbench]\n"
        "if core_dir:\n"
        "    import glob\n"
        "    found = glob.glob(core_dir + '/_core*.so')\n"
        "    if found:\n"
        "        spec = importlib.util.spec_from_file_location('facet._core', found[0])\n"
        "        class CoreFinder:\n"
        "            @staticmethod\n"
        "            def find_spec(name, path=None, target=None):\n"
        "                return spec if name == 'facet._core' else None\n"
        "        sys.meta_path.insert(0, CoreFinder)\n"
        "import harness\n"
        "import facet._core, facet.planarize, facet.lift, facet.panels, facet.plan, facet.io\n"
        "import ezdxf, shapely, scipy.spatial\n"
        "sys.stderr.write('fuzz_python: facet._core from %s\\n' % facet._core.__file__)\n"
        "one_input = harness.one_input\n",
        Py_file_input, globals, globals);
    if (r == NULL) fail_python("cannot import the harness");
    Py_DECREF(r);
    one_input = PyDict_GetItemString(globals, "one_input");
    Py_XINCREF(one_input);
    Py_DECREF(globals);
    if (one_input == NULL) fail_python("harness.one_input missing");
    PyEval_SetTrace(trace, NULL);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (one_input == NULL) LLVMFuzzerInitialize(NULL, NULL);
    PyObject *bytes = PyBytes_FromStringAndSize((const char *)data, (Py_ssize_t)size);
    if (bytes == NULL) fail_python("out of memory");
    previous = 0;
    PyObject *r = PyObject_CallOneArg(one_input, bytes);
    Py_DECREF(bytes);
    if (r == NULL) fail_python("FINDING: the harness raised");
    Py_DECREF(r);
    return 0;
}

/* ------------------------------------------------------------------------
 * Structure-aware mutations for the text formats (every reader but the
 * first byte's selector is line based): half of the mutations work on whole
 * lines or numbers -- duplicate, delete or swap a line, replace a number by
 * an extreme one, change the selector -- the other half are libFuzzer's own
 * byte mutations. Absent from the replay build (no LLVMFuzzerMutate there).
 * ---------------------------------------------------------------------- */
#ifdef FACET_CUSTOM_MUTATOR

static uint32_t rng(uint32_t *state)
{
    *state ^= *state << 13;
    *state ^= *state >> 17;
    *state ^= *state << 5;
    return *state;
}

/* Start offsets of the lines of data[1..size) (at most max), count returned. */
static size_t line_starts(const uint8_t *data, size_t size, size_t *starts, size_t max)
{
    size_t n = 0;
    if (size <= 1) return 0;
    starts[n++] = 1;
    for (size_t i = 1; i + 1 < size && n < max; i++)
        if (data[i] == '\n') starts[n++] = i + 1;
    return n;
}

static size_t line_end(const uint8_t *data, size_t size, size_t start)
{
    while (start < size && data[start] != '\n') start++;
    return start < size ? start + 1 : size; /* past the newline */
}

size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed)
{
    uint32_t state = seed | 1u;
    static const char *numbers[] = {"nan", "inf", "-inf", "1e308", "-1e308", "1e16", "4.9e-324",
                                    "0", "-0", "-1", "2147483647", "2147483648", "-2147483649",
                                    "99999999999999999999", "1e-7", "6500000.001", "0x10", "1_0"};
    size_t starts[4096];
    switch (rng(&state) % 8) {
    case 0: /* duplicate a line */
    case 1: {
        size_t n = line_starts(data, size, starts, 4096);
        if (n == 0) break;
        size_t a = starts[rng(&state) % n], b = line_end(data, size, a), len = b - a;
        if (size + len > max_size) break;
        memmove(data + b + len, data + b, size - b);
        memcpy(data + b, data + a, len);
        return size + len;
    }
    case 2: { /* delete a line */
        size_t n = line_starts(data, size, starts, 4096);
        if (n == 0) break;
        size_t a = starts[rng(&state) % n], b = line_end(data, size, a);
        memmove(data + a, data + b, size - b);
        return size - (b - a);
    }
    case 3: { /* swap two lines (by rotating the span between them) */
        size_t n = line_starts(data, size, starts, 4096);
        if (n < 2) break;
        size_t i = rng(&state) % n, j = rng(&state) % n;
        if (i == j) break;
        if (i > j) { size_t t = i; i = j; j = t; }
        size_t a = starts[i], b = line_end(data, size, a), c = starts[j], d = line_end(data, size, c);
        uint8_t tmp[8192];
        if (d - a > sizeof tmp || b > c) break;
        size_t o = 0;
        memcpy(tmp + o, data + c, d - c), o += d - c;
        memcpy(tmp + o, data + b, c - b), o += c - b;
        memcpy(tmp + o, data + a, b - a), o += b - a;
        memcpy(data + a, tmp, o);
        return size;
    }
    case 4:
    case 5: { /* replace a number by an extreme one */
        size_t idx[1024], n = 0;
        for (size_t i = 1; i < size && n < 1024; i++)
            if ((data[i] >= '0' && data[i] <= '9') && (i == 1 || !((data[i - 1] >= '0' && data[i - 1] <= '9') ||
                                                                 data[i - 1] == '.' || data[i - 1] == '-')))
                idx[n++] = i;
        if (n == 0) break;
        size_t a = idx[rng(&state) % n], b = a;
        while (b < size && ((data[b] >= '0' && data[b] <= '9') || data[b] == '.' || data[b] == 'e' ||
                            data[b] == 'E' || data[b] == '-' || data[b] == '+'))
            b++;
        const char *r = numbers[rng(&state) % (sizeof numbers / sizeof numbers[0])];
        size_t len = strlen(r);
        if (size - (b - a) + len > max_size) break;
        memmove(data + a + len, data + b, size - b);
        memcpy(data + a, r, len);
        return size - (b - a) + len;
    }
    case 6: /* another reader for the same bytes */
        if (size > 0) {
            data[0] = (uint8_t)rng(&state);
            return size;
        }
        break;
    default:
        break;
    }
    return LLVMFuzzerMutate(data, size, max_size);
}
#endif
