# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reading and writing mesh files as text.

Shared by the OBJ, OFF and compas readers and writers: text decoding that
never fails on a stray byte in a comment, numbers parsed with the line they
came from in the error, and writing that never leaves half a file behind.
"""

import codecs
import contextlib
import errno
import os
import secrets
import threading

import numpy as np

from facet.errors import MeshError

__all__ = [
    "read_lines",
    "read_text",
    "split_lines",
    "parse_float",
    "parse_int",
    "check_writable_mesh",
    "write_text",
    "write_replacing",
    "staged",
    "when_staged",
    "put_in_place",
    "format_float",
    "reading_progress",
    "PROGRESS_EVERY",
]

#: Lines or records a mesh reader reads between two progress calls.
PROGRESS_EVERY = 16384


def reading_progress(progress, path):
    """``report(done, total)`` for a mesh reader: ``progress(done, total)`` when `progress`
    is given; True from it cancels (:class:`facet.Cancelled`, "reading NAME cancelled")."""
    from facet.errors import report_progress

    what = f"reading {os.path.basename(os.fspath(path))}"

    def report(done, total):
        report_progress(progress, done, total, what)

    return report

#: Per thread, while :func:`staged` runs: ``stage``, [(temporary file, its path)] and
#: clean-ups in order, and ``depth``, the blocks open.
_local = threading.local()


def _stage():
    if not hasattr(_local, "stage"):
        _local.stage, _local.depth = [], 0
    return _local.stage


def read_lines(path):
    """Read a text file as a list of lines.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    list of str
        Lines without their ends; ``lines[k]`` is line ``k + 1``. Windows and
        old Mac line ends are accepted. The text is decoded by :func:`read_text`
        (UTF-8, or UTF-16 with its byte order mark); bytes that do not decode
        become U+FFFD, so a stray byte in a comment does not stop the reading.

    Raises
    ------
    OSError
        When the file cannot be opened.
    """
    return split_lines(read_text(path))  # line ends are split_lines' to translate


def read_text(path):
    """Read a text file whole, line ends as they are.

    UTF-8 (with or without a byte order mark), or UTF-16 or UTF-32 when the file starts
    with its byte order mark (what Windows tools write as "Unicode": PowerShell's ``>``,
    Notepad, .NET scripts). Bytes that do not decode become U+FFFD, so a stray byte in a
    comment does not stop the reading. A byte order mark is dropped.

    Raises
    ------
    OSError
        When the file cannot be opened.
    """
    with open(path, "rb") as stream:
        data = stream.read()
    text = data.decode(bom_encoding(data) or "utf-8", errors="replace")
    return text[1:] if text.startswith("\ufeff") else text


def bom_encoding(data):
    """"utf-16" or "utf-32" when the bytes start with that encoding's byte order mark,
    "utf-8-sig" with UTF-8's, else None."""
    for mark, name in ((codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"),
                       (codecs.BOM_UTF16_LE, "utf-16"), (codecs.BOM_UTF16_BE, "utf-16"),
                       (codecs.BOM_UTF8, "utf-8-sig")):
        if data.startswith(mark):
            return name
    return None


def split_lines(text):
    """The lines of decoded text, without their ends (Windows, old Mac or Unix) and without a
    byte order mark; ``lines[k]`` is line ``k + 1``."""
    if text.startswith("\ufeff"):
        text = text[1:]
    return text.replace("\r\n", "\n").replace("\r", "\n").split("\n")


def _shown(token, limit=40):
    return token if len(token) <= limit else token[:limit] + "..."


def parse_float(token, source, line):
    """Read one coordinate.

    Parameters
    ----------
    token : str
    source : str or os.PathLike
        File name for the error message.
    line : int
        Line number for the error message.

    Returns
    -------
    float
        May be NaN or infinite; :func:`facet.io.checks.build_mesh` refuses those.

    Raises
    ------
    MeshError
        ``"bad.obj: line 4: cannot read 'abc' as a number"``.
    """
    try:
        if _plain(token):
            return float(token)
    except ValueError:
        pass
    raise MeshError(f"cannot read {_shown(token)!r} as a number", source=source, line=line)


def parse_int(token, source, line, what="an integer"):
    """Read one integer (an index or a count).

    Parameters
    ----------
    token : str
    source : str or os.PathLike
    line : int
    what : str
        What the integer is, for the message (``"a vertex index"``).

    Returns
    -------
    int

    Raises
    ------
    MeshError
        ``"x.off: line 9: cannot read '2.5' as a vertex index"``.
    """
    try:
        if _plain(token):
            return int(token)
    except ValueError:
        pass
    raise MeshError(f"cannot read {_shown(token)!r} as {what}", source=source, line=line)


def _plain(token):
    """Whether a number is written as mesh files write them: ASCII, no digit separators
    (Python's float() and int() would read '1_5' as 15 and other scripts' digits too)."""
    return token.isascii() and "_" not in token


def check_writable_mesh(mesh, path):
    """Refuse to write a mesh with NaN or infinite coordinates.

    Raises
    ------
    MeshError
        ``"out.obj: vertex 5 has a non-finite coordinate; nothing written"``.
    """
    finite = np.isfinite(mesh.vertices).all(axis=1)
    if not finite.all():
        vertex = int(np.argmin(finite))
        raise MeshError(
            f"vertex {vertex} has a non-finite coordinate; nothing written",
            source=path,
            vertex=vertex,
        )


def format_float(value):
    """Shortest text that reads back to exactly the same float64 (``repr``).

    Parameters
    ----------
    value : float

    Returns
    -------
    str
        At most 17 significant digits; ``1.0`` for one, ``-0.0`` kept.
    """
    return repr(float(value))


def write_text(path, chunks):
    """Write text to `path` so that a failure leaves no half-written file
    (:func:`write_replacing`).

    Parameters
    ----------
    path : str or os.PathLike
    chunks : iterable of str
        Pieces of the file, written one after the other.

    Raises
    ------
    OSError
        Naming `path` (not the temporary file) when its folder is missing or not
        writable.
    """
    def write(partial):
        with open(partial, "w", encoding="utf-8", newline="\n") as stream:
            for chunk in chunks:
                stream.write(chunk)

    write_replacing(path, write)


def write_replacing(path, write, suffix=""):
    """Call ``write(partial)`` to write a new temporary file beside `path`
    (``NAME.<random>.part`` + `suffix`, a name no other file has, with the mode new files
    get), then put it in `path`'s place. A failure or Ctrl+C on the way leaves no
    temporary file and no half-written `path`; an error of the file system names `path`.

    Parameters
    ----------
    path : str or os.PathLike
    write : callable
        Writes the whole file to the path it is given (``doc.saveas``, ``fig.savefig``).
    suffix : str
        Ends the temporary name, for writers that choose the format by it (``".png"``).
    """
    path = os.fspath(path)
    # through a symbolic link to the file it names (replacing the link by a file of its
    # own left the linked file, in a project folder, as it was)
    target = os.path.realpath(path) if os.path.islink(path) else path
    handle, partial = _create_beside(target, suffix)
    os.close(handle)
    try:
        write(partial)
        if getattr(_local, "depth", 0):
            _stage().append((partial, target))
            return
        _put_in_place(partial, target)
    except BaseException:
        try:
            os.remove(partial)
        except OSError:
            pass
        raise


def put_in_place(partial, path):
    """Move the finished file ``partial`` (written beside ``path`` by someone else, e.g. a
    worker process) to ``path``: now, or inside :func:`staged` when its files take their
    places (after an error there, ``partial`` is removed and ``path`` is as it was)."""
    partial, path = os.fspath(partial), os.fspath(path)
    if getattr(_local, "depth", 0):
        _stage().append((partial, path))
    else:
        _put_in_place(partial, path)


def _put_in_place(partial, path):
    try:
        os.replace(partial, path)
    except OSError as error:  # (a folder of that name): the path asked for, not ours
        raise type(error)(error.errno, error.strerror, path) from None


@contextlib.contextmanager
def staged():
    """Files this thread writes with :func:`write_replacing` in the block take their places
    together when it ends without an error, and the clean-ups given to
    :func:`when_staged` run then; after an error or Ctrl+C their temporary files are
    removed and the files are as they were. For outputs that belong together: a run's cut
    sheets, schedule and previews, which a failure of its STEP file must not leave beside
    an older one. A nested block that fails drops its own files; one that ends well leaves
    them to the outermost. (Putting the files in place is a rename each: if one of those
    fails, as on a folder of that name, the ones before it stay replaced.)"""
    stage = _stage()
    start = len(stage)
    _local.depth += 1
    try:
        yield
    except BaseException:
        _drop(stage[start:])
        del stage[start:]
        raise
    finally:
        _local.depth -= 1
    if _local.depth:
        return
    try:
        for item in stage:
            if callable(item):
                item()
            else:
                _put_in_place(*item)
    finally:
        _drop(stage)
        stage.clear()


def _drop(items):
    """Remove the temporary files of `items` that are still there."""
    for item in items:
        if not callable(item) and os.path.exists(item[0]):
            try:
                os.remove(item[0])
            except OSError:
                pass


def when_staged(action):
    """Run ``action()`` now, or inside :func:`staged` when its files take their places."""
    if getattr(_local, "depth", 0):
        _stage().append(action)
    else:
        action()


def _create_beside(path, suffix=""):
    """A new file ``NAME.<random>.part`` + `suffix` beside `path`, created exclusively
    (never another file of that name) with the mode new files get (the umask applies):
    (descriptor, name). An error names `path`."""
    folder, name = os.path.split(os.path.abspath(path))
    if len(os.fsencode(f"{name}.12345678.part{suffix}")) > 255:  # (a name near the limit)
        name = ".facet"
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    for _attempt in range(100):
        partial = os.path.join(folder, f"{name}.{secrets.token_hex(4)}.part{suffix}")
        try:
            return os.open(partial, flags, 0o666), partial
        except FileExistsError:
            continue
        except OSError as error:
            raise type(error)(error.errno, error.strerror, path) from None
    raise FileExistsError(errno.EEXIST, "no free name for a temporary file beside it", path)


def write_mesh_records(path, mesh, header, vertex_prefix, face_record, footer=""):
    """Write `header`, then one line per vertex and one per face, in large chunks.

    Parameters
    ----------
    path : str or os.PathLike
    mesh : PolyMesh
        Checked with :func:`check_writable_mesh` first: nothing is written when
        a coordinate is NaN or infinite.
    header : str
        Text before the vertices (ends with a newline).
    vertex_prefix : str
        Written before each vertex's three coordinates (``"v "`` for OBJ).
    face_record : callable
        ``face_record(face)`` gives the line of a face (a list of indices from
        0), without the newline; called once per face, in order.
    footer : str
        Text after the faces.
    """
    check_writable_mesh(mesh, path)

    def chunks():
        yield header
        lines = []
        for x, y, z in mesh.vertices.tolist():
            lines.append(f"{vertex_prefix}{format_float(x)} {format_float(y)} {format_float(z)}\n")
            if len(lines) >= 4096:
                yield "".join(lines)
                lines = []
        for face in mesh.faces():
            lines.append(face_record(face) + "\n")
            if len(lines) >= 4096:
                yield "".join(lines)
                lines = []
        yield "".join(lines) + footer

    write_text(path, chunks())
