"""Reading and writing the user's files so that nothing is lost.

Reading: only a regular file is read, checked on the open file itself (opened without blocking, so a
FIFO with no writer is refused at once instead of waiting for ever), and never more than a limit.
Writing: the whole file or nothing (a temporary file renamed over the path), only over a regular file,
through a symbolic link to the file it names (the link stays a link), and never over a file the same
command has read: an input is never an output (:func:`inputs_guarded`).
"""

from __future__ import annotations

import os
import stat
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import BinaryIO


class InputError(ValueError):
    """A bad input file or value; ``str(e)`` is a one-line message naming the file and the problem."""


FileId = tuple[int, int]
"""A file's identity: (device, inode); two paths, links or hard links name one file when these agree."""

_SPECIAL_FILES = (
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISFIFO, "a FIFO"),
    (stat.S_ISSOCK, "a socket"),
)

# What the running command has read (set by :func:`inputs_guarded`); None when nothing is guarded (the
# visualiser's own saves may replace a file it loaded: the user asked for exactly that).
_inputs_read: dict[FileId, str] | None = None


def _kind(mode: int) -> str | None:
    for test, kind in _SPECIAL_FILES:
        if test(mode):
            return kind
    return None


def file_id(path: Path | str) -> FileId | None:
    """The identity of the file ``path`` names (through links), or None when nothing is there."""
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return None
    return st.st_dev, st.st_ino


@contextmanager
def inputs_guarded() -> Iterator[None]:
    """While a command runs, every file it reads through :func:`reading` is remembered, and
    :func:`replace_atomically` refuses to replace any of them (however the output path reaches it: the
    same name, a symbolic link, a hard link)."""
    global _inputs_read
    outer = _inputs_read
    _inputs_read = {} if outer is None else outer
    try:
        yield
    finally:
        _inputs_read = outer


def refuse_input_as_output(path: Path | str, inputs: dict[str, Path | str]) -> None:
    """Refuse, before any work, an output ``path`` that names the same file as one of ``inputs`` (an
    option's name → the path it was given)."""
    out, where = file_id(path), os.path.realpath(path)
    for option, given in inputs.items():
        if (out is not None and file_id(given) == out) or os.path.realpath(given) == where:
            raise InputError(
                f"{path}: is the same file as {option} {given}; an output never replaces an input or "
                "another output (give another path)"
            )


def _remember_input(fid: FileId, path: Path | str) -> None:
    if _inputs_read is not None:
        _inputs_read[fid] = str(path)


def _refuse_read_input(target: Path, given: Path | str) -> None:
    if not _inputs_read:
        return
    fid = file_id(target)
    if fid is not None and fid in _inputs_read:
        raise InputError(
            f"{given}: is this command's input {_inputs_read[fid]}; refusing to write over an input "
            "(give another output path)"
        )


@contextmanager
def reading(path: Path | str) -> Iterator[BinaryIO]:
    """The regular file ``path`` opened for reading, every failure an :class:`InputError` naming it.

    Opened with O_NONBLOCK so that a FIFO with no writer does not block the open; its type is then read
    from the open file (not from the path, which could change in between) and anything but a regular
    file is refused; reads stay non-blocking."""
    p = Path(path)
    try:
        fd = os.open(p, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        raise InputError(f"{p}: no such file") from None
    except IsADirectoryError:
        raise InputError(f"{p}: is a directory, not a file") from None
    except OSError as e:
        raise InputError(f"{p}: cannot read ({e.strerror})") from None
    try:
        st = os.fstat(fd)
        problem = _not_readable(p, st.st_mode)
        if problem:
            raise InputError(problem)
        # Left non-blocking: a regular file never waits, and a file that only claims to be one (a
        # procfs file such as /proc/kmsg) cannot make a read wait for ever either.
        f = os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
    _remember_input((st.st_dev, st.st_ino), p)
    try:
        with f:
            yield f
    except UnicodeDecodeError:
        raise InputError(f"{p}: not UTF-8 text") from None
    except OSError as e:
        raise InputError(f"{p}: cannot read ({e.strerror})") from None


def _not_readable(p: Path | str, mode: int) -> str | None:
    if stat.S_ISDIR(mode):
        return f"{p}: is a directory, not a file"
    if stat.S_ISREG(mode):
        return None
    kind = _kind(mode) or "not a regular file"
    return f"{p}: is {kind}, not a regular file; only a regular file is read (save the input to a file)"


def check_readable(path: Path | str) -> None:
    """Refuse, without opening it, a path that is not a regular file (for a library that opens the file
    itself, such as pyarrow): a FIFO would block it."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    problem = _not_readable(path, mode)
    if problem:
        raise InputError(problem)


def too_large(p: Path | str, limit: int) -> InputError:
    """The error for a file over ``limit`` bytes (not raised: the caller raises it)."""
    return InputError(f"{p}: file is too large (more than {limit:,} bytes)")


def read_bytes(path: Path | str, limit: int) -> bytes:
    """A regular file of at most ``limit`` bytes; the limit is on what is read, not on what ``stat``
    says (a file may grow while it is read)."""
    with reading(path) as f:
        data = f.read(limit + 1)
    if data is None:  # a non-blocking read with nothing to give
        raise InputError(f"{path}: cannot read (it has nothing to give without waiting)")
    if len(data) > limit:
        raise too_large(path, limit)
    return data


def read_text(path: Path | str, limit: int) -> str:
    """A regular UTF-8 file of at most ``limit`` bytes (:func:`read_bytes`)."""
    try:
        return read_bytes(path, limit).decode("utf-8")
    except UnicodeDecodeError:
        raise InputError(f"{path}: not UTF-8 text") from None


def read_lines(path: Path | str, limit: int) -> Iterator[tuple[int, str]]:
    """The file's non-blank lines with their numbers, read one at a time (a long trace or schedule is
    never held whole), and at most ``limit`` bytes in all, however long a line."""
    read = 0
    with reading(path) as f:
        n = 0
        while raw := f.readline(limit - read + 1):
            read += len(raw)
            if read > limit:
                raise too_large(path, limit)
            n += 1
            line = raw.decode("utf-8")
            if line.strip():
                yield n, line


# ---------------------------------------------------------------------------------------------- writing
def make_folder(path: Path) -> list[Path]:
    """Make the folder ``path`` and its missing parents; the folders made, deepest first (for
    :func:`remove_if_empty`)."""
    missing = []
    p = path
    while not p.exists() and p != p.parent:
        missing.append(p)
        p = p.parent
    path.mkdir(parents=True, exist_ok=True)
    return missing


def remove_if_empty(made: list[Path]) -> None:
    """Remove the folders :func:`make_folder` made that are still empty: a command that failed leaves no
    empty folder behind."""
    for folder in made:
        try:
            folder.rmdir()
        except OSError:  # not empty (or gone): kept
            return


def not_regular(path: Path | str) -> str | None:
    """Why an output could not replace what ``path`` names (a device, a FIFO, a socket: a rename over it
    would replace the node itself, e.g. the machine's /dev/null), or None: nothing there, or a regular
    file (through a symbolic link, the file it names)."""
    try:
        mode = os.stat(path).st_mode
    except (FileNotFoundError, NotADirectoryError):
        return None
    kind = _kind(mode)
    if kind:
        return f"{path}: is {kind}, not a regular file; refusing to replace it (give a file's path)"
    return None


def _refuse_special(path: Path | str) -> None:
    problem = not_regular(path)
    if problem:
        raise InputError(problem)


def write_target(path: Path | str, through_links: bool = True) -> Path:
    """Where a write to ``path`` lands: ``path`` itself, or through symbolic links the file they name
    (written through, as a shell's ``>`` does: the link stays a link). A file whose name apf-viz makes
    itself (a trace in a traces folder, a figure, a plot, a table beside ``--out``: ``through_links``
    False) is never written through a link: whatever the link points at was not named by the user."""
    p = Path(path)
    if not p.is_symlink():
        return p
    if not through_links:
        raise InputError(
            f"{path}: is a symbolic link; a file apf-viz names itself is never written through one "
            "(remove the link, or choose another folder)"
        )
    return Path(os.path.realpath(p))


def check_writable(path: Path | str, through_links: bool = True) -> None:
    """Refuse, before any work is done, an output path that :func:`write_atomic` could not write: its
    folder missing or read-only, the path a folder, anything but a regular file (:func:`not_regular`), or
    a file this command has read. The message names the path as given."""
    p = write_target(path, through_links)
    if p.is_dir():
        raise InputError(f"{path}: is a directory, not a file")
    _refuse_special(p)
    _refuse_read_input(p, path)
    folder = p.parent
    if not folder.is_dir():
        raise InputError(f"{path}: cannot write: folder {str(folder)!r} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"{path}: cannot write: folder {str(folder)!r} is not writable")


def replace_atomically(
    path: Path | str, write: Callable[[str], None], suffix: str = ".tmp", through_links: bool = True
) -> None:
    """The whole file or nothing: ``write(temporary path)`` in the same folder, then rename over ``path``
    (through a symbolic link, over the file it names, unless ``through_links`` is False: see
    :func:`write_target`; a table or an image written by another library goes through here too). Never
    over a file this command has read (:func:`inputs_guarded`)."""
    p = write_target(path, through_links)
    _refuse_special(p)  # before a temporary file is made beside it (in /dev, for /dev/null)
    _refuse_read_input(p, path)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=suffix, dir=p.parent or ".")
    os.close(fd)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; a saved file gets the usual permissions
        write(tmp)
        _refuse_special(p)  # again at the rename: the path may have changed meanwhile
        _refuse_read_input(p, path)
        os.replace(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_atomic(path: Path | str, text: str, through_links: bool = True) -> None:
    """Write the whole text file or nothing (fsynced before the rename; ``through_links``: see
    :func:`write_target`)."""

    def write(tmp: str) -> None:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())

    replace_atomically(path, write, through_links=through_links)
