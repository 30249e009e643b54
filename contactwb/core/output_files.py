"""Files written safely (issue 25): each through a temporary file in the same
folder (created exclusively, never through a symbolic link), renamed into
place once complete. A run stopped meanwhile leaves no partial file (the CLI's
cancel handler removes the temporaries listed here), two runs never interleave
in one file, and a symbolic link already at the target is replaced, never
written through."""
import contextlib
import errno
import os
import threading

_lock = threading.Lock()
_pending = set()  # temporary files being written
_stopped = False


def stop():
    """For a cancel handler: no new temporary file from now on; returns those
    being written (to remove)."""
    global _stopped
    with _lock:
        _stopped = True
        return list(_pending)


SYSTEM_FOLDERS = ("/dev", "/proc", "/sys")


class UnsafeTarget(ValueError):
    """An output path that must not be written (a device, a folder, a system folder)."""


def check_target(path):
    """Refuses (UnsafeTarget) an output that is not a regular file or a new
    name: a device, a FIFO or a folder already there, or a name inside /dev,
    /proc or /sys (root would create files there)."""
    text = os.fsdecode(path)
    folder = os.path.realpath(os.path.dirname(os.path.abspath(text)))
    if any(folder == top or folder.startswith(top + "/") for top in SYSTEM_FOLDERS):
        raise UnsafeTarget(f"'{text}' is in the system folder {folder}: write the output elsewhere")
    if os.path.lexists(text) and not os.path.islink(text) and not os.path.isfile(text):
        raise UnsafeTarget(f"'{text}' exists and is not a regular file (a folder or a device): name a file")


def _temporary_beside(path):
    check_target(path)
    folder = os.path.dirname(os.path.abspath(path))
    base = os.path.basename(path)
    for attempt in range(100):
        # The same ending as the target: writers that choose a format by it still do.
        temporary = os.path.join(folder, f".{os.getpid()}-{threading.get_ident() % 100000}-{attempt}.{base}")
        try:
            fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o666)
        except FileExistsError:
            continue
        with _lock:
            if _stopped:
                os.close(fd)
                os.unlink(temporary)
                raise OSError(errno.ECANCELED, "cancelled", path)
            _pending.add(temporary)
        return fd, temporary
    raise OSError(errno.EEXIST, "cannot make a temporary file", path)


def _forget(temporary):
    """A temporary no longer pending, and gone (renamed into place or removed)."""
    with _lock:
        _pending.discard(temporary)
    with contextlib.suppress(FileNotFoundError):
        os.unlink(temporary)


@contextlib.contextmanager
def replaced(path):
    """Yields the name of a new temporary file beside `path` for a writer
    that opens files by name (the core's write_ply); renamed to `path` when
    the block ends without an exception, removed otherwise."""
    fd, temporary = _temporary_beside(path)
    os.close(fd)
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        _forget(temporary)


@contextlib.contextmanager
def output_file(path, mode="w", **open_args):
    """open(path, mode) written through a temporary file, renamed into place
    at the end (see the module's text)."""
    fd, temporary = _temporary_beside(path)
    try:
        with os.fdopen(fd, mode, **open_args) as stream:
            yield stream
        os.replace(temporary, path)
    finally:
        _forget(temporary)
