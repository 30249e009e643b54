"""The exit-code contract shared by every `contacts` command (issue 25).

    0    done
    2    usage error (a bad option or value)
    3    unreadable or refused input (no such file, damaged, beyond a limit)
    4    the analysis failed (OCCT error, out of memory, interlocked parts),
         or the output could not be written (disk full, standard output closed)
    5    internal error (a bug: please report it)
    130  cancelled (SIGINT, Ctrl+C, or SIGTERM): no partial output is left
    141  standard output closed by its reader (`| head -1`): quietly, as a
         tool killed by SIGPIPE

`run(name, body)` runs a command's body (a function returning the exit code)
under that contract. SIGINT and SIGTERM are taken by a thread of their own
(blocked in every other thread, the core's workers included), so they end the
process within milliseconds even while the core runs without the GIL; files
being written (output_files) are removed first."""
import contextlib
import errno
import os
import signal
import sys
import threading

EXIT_OK, EXIT_USAGE, EXIT_INPUT, EXIT_FAILED, EXIT_INTERNAL, EXIT_CANCELLED = 0, 2, 3, 4, 5, 130
EXIT_BROKEN_PIPE = 128 + signal.SIGPIPE



# The file the running command works on, once it has read its arguments (working_on): named in
# the errors run() reports itself (out of memory outside a command's own handlers).
_subject = None


def working_on(path):
    """Names the file the running command works on, for the errors run() reports itself."""
    global _subject
    _subject = path


def naming_the_file(text, path):
    """An error's text with the file named once: the core's errors name it already (its full
    path), a Python error or a document's body error may not."""
    return text if os.path.basename(path) in text else f"{text} (file '{path}')"


def out_of_memory_message(error, path):
    """What a command says of a MemoryError: the core's text (which names the file) or Python's
    own (no text), with the file named once."""
    return naming_the_file(str(error) if "out of memory" in str(error) else "out of memory", path)


class UsageError(Exception):
    """A bad option value found after argparse (exit 2)."""


def _cancel_watcher(name, signals):
    caught = signal.sigwait(signals)
    # Looked up, not imported: this module stays light (stdlib only), so the
    # handler is in place before the extension loads.
    output_files = sys.modules.get("contactwb.core.output_files")
    for path in output_files.stop() if output_files else ():
        with contextlib.suppress(OSError):
            os.unlink(path)
    with contextlib.suppress(OSError):
        os.write(2, f"{name}: cancelled ({signal.Signals(caught).name})\n".encode())
    os._exit(EXIT_CANCELLED)


def install_cancel_handler(name):
    """SIGINT and SIGTERM end the process with exit 130 from any point of the
    run (inside OCCT and the core's loops too). Call before starting threads."""
    signals = {signal.SIGINT, signal.SIGTERM}
    if threading.current_thread() is not threading.main_thread():
        return
    signal.pthread_sigmask(signal.SIG_BLOCK, signals)
    threading.Thread(target=_cancel_watcher, args=(name, signals), name="contacts-cancel", daemon=True).start()


def _check_standard_output(name):
    """A closed standard output (`>&-`): keep fd 1 taken (a file opened later
    would get it and receive OCCT's prints) and refuse before any work."""
    try:
        os.fstat(1)
    except OSError:
        fd = os.open(os.devnull, os.O_WRONLY)
        if fd != 1:
            os.dup2(fd, 1)
            os.close(fd)
        print(f"{name}: standard output is closed; nothing to write to", file=sys.stderr)
        return False
    if sys.stdout is None:
        sys.stdout = open(1, "w", closefd=False)
    return True


def _quiet_standard_output():
    """After a broken pipe: point stdout at /dev/null so the interpreter's
    final flush does not complain."""
    with contextlib.suppress(OSError):
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, 1)
        os.close(fd)


def finish_output(name):
    """Flushes standard output; an error there is the command's (exit 4), a
    reader gone is quiet (141). Returns None when all was written."""
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _quiet_standard_output()
        return EXIT_BROKEN_PIPE
    except OSError as error:
        _quiet_standard_output()
        print(f"{name}: cannot write the output: {error.strerror or error}", file=sys.stderr)
        return EXIT_FAILED
    return None


def run(name, body, own_process=True):
    """Runs `body()` (returning an exit code) under the contract above. With
    own_process (the command line, not a call from Python code), also checks
    standard output and takes SIGINT/SIGTERM for the rest of the process."""
    working_on(None)
    if own_process:
        if not _check_standard_output(name):
            return EXIT_FAILED
        install_cancel_handler(name)
    try:
        code = body()
    except KeyboardInterrupt:
        print(f"{name}: cancelled", file=sys.stderr)
        return EXIT_CANCELLED
    except BrokenPipeError:
        _quiet_standard_output()
        return EXIT_BROKEN_PIPE
    except UsageError as error:
        print(f"{name}: {error}", file=sys.stderr)
        return EXIT_USAGE
    except OSError as error:
        if error.errno in (errno.ENOSPC, errno.EBADF, errno.EIO, errno.EDQUOT) and error.filename is None:
            _quiet_standard_output()
            print(f"{name}: cannot write the output: {error.strerror}", file=sys.stderr)
            return EXIT_FAILED
        raise
    except MemoryError:
        print(f"{name}: {naming_the_file('out of memory', _subject) if _subject else 'out of memory'}",
              file=sys.stderr)
        return EXIT_FAILED
    except SystemExit:
        raise
    except Exception as error:  # a bug: say so, without a traceback unless asked
        return internal_error(name, error)
    flushed = finish_output(name)
    return code if flushed is None else flushed


def internal_error(name, error):
    """For an `except Exception as error:` block, a bug: re-raises it with its
    traceback when $CONTACTS_DEBUG is set, else says so in one line: exit 5."""
    if os.environ.get("CONTACTS_DEBUG"):
        raise  # the exception being handled, its traceback whole
    print(f"{name}: internal error ({type(error).__name__}: {error}); "
          "set CONTACTS_DEBUG=1 for the traceback and please report it", file=sys.stderr)
    return EXIT_INTERNAL


def unsafe_output(name, option, path):
    """Whether `path`, given to `option`, is no place to write (output_files.check_target):
    if so, says why as `name: option <why>` (then the caller exits 2)."""
    from contactwb.core import output_files
    try:
        output_files.check_target(path)
    except output_files.UnsafeTarget as error:
        print(f"{name}: {option} {error}", file=sys.stderr)
        return True
    return False


def display_name(path):
    """A path as text for messages (undecodable bytes escaped)."""
    return os.fsdecode(path) if isinstance(path, bytes) else path


def escape_controls(text):
    """Control characters (terminal escapes, CR, LF, ...) shown as \\x.. so a
    name cannot retitle the terminal or fake a line of the output."""
    from contactwb.core.analysis import printable
    return printable(text)


def nonnegative_count(text):
    """argparse type: an integer from 0 to 2**63 - 1."""
    import argparse
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {text!r}")
    if value < 0 or value >= 2 ** 63:
        raise argparse.ArgumentTypeError(f"must be an integer from 0 to {2 ** 63 - 1}, got {text}")
    return value


def finite_number(low=None, low_open=False, high=None):
    """argparse type: a finite number within [low, high] (low excluded when low_open)."""
    import argparse
    import math

    def parse(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {text!r}")
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"must be a finite number, got {text}")
        if low is not None and (value < low or (low_open and value == low)):
            raise argparse.ArgumentTypeError(f"must be {'above' if low_open else 'at least'} {low:g}, got {text}")
        if high is not None and value > high:
            raise argparse.ArgumentTypeError(f"must be at most {high:g}, got {text}")
        return value
    return parse
