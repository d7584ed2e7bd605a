r"""An output folder written all at once: staged beside its place, locked, then renamed into it.

:class:`OutputFolder` is how :meth:`~symctl.report.results.PaperResults.write`
and ``symctl paper`` write a folder. It promises that the folder ``out`` is at
every moment either the old complete one (or absent) or the new complete one:

1. **Checked before any work.** :func:`check_output_folder` refuses an empty
   name, a file, a parent that cannot hold a folder, and an existing folder
   holding anything but the regular files of an earlier run (so that replacing
   it never deletes a user's files).
2. **Locked.** ``<out>.lock`` (beside ``out``) is held with ``fcntl.flock`` for
   the whole run; a second run on the same folder is refused at once with a
   :class:`~symctl.errors.ParameterError` naming the process that holds it
   (non-blocking: a refusal is clearer than a silent wait). The lock file is
   removed when the run ends.
3. **Staged.** Everything is written into a fresh folder ``.<name>.tmp-<hex>``
   beside ``out`` (same parent, so same file system and renames are atomic).
4. **Committed by rename.** When everything is written, the staged folder and
   ``out`` are exchanged in one step (Linux ``renameat2(RENAME_EXCHANGE)``),
   or, where that is not available, by the rename dance
   ``out -> .<name>.old-<hex>``, ``staged -> out``, then the old one is removed.
   SIGINT and SIGTERM are held back during the commit.

What happens on each failure:

=====================================  ==============================================
failure                                result
=====================================  ==============================================
error or signal while writing          staged folder removed; ``out`` untouched
second run on the same ``out``         refused before any work; the first goes on
``out -> .old`` rename fails           nothing moved; staged folder removed; error
``staged -> out`` rename fails         ``.old`` renamed back to ``out``; staged
                                       folder removed; error
removing ``.old`` fails                ``out`` is the new folder; ``.old`` stays and
                                       the next run on ``out`` removes it
process killed (SIGKILL, power loss)   ``.tmp-``/``.old-`` folders may stay; the next
                                       run on ``out`` (under the lock) removes them,
                                       and renames ``.old-`` back to ``out`` when
                                       ``out`` is missing
=====================================  ==============================================

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> from symctl.report.output import OutputFolder
>>> with tempfile.TemporaryDirectory() as parent:
...     with OutputFolder(Path(parent) / "run") as folder:
...         _ = (folder.staging / "results.json").write_text("{}")
...         (Path(parent) / "run").exists()
...     sorted(p.name for p in Path(parent).iterdir()), (Path(parent) / "run").is_dir()
False
(['run'], True)
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import secrets
import shutil
import signal
import stat
import time
from pathlib import Path
from types import TracebackType

from symctl.errors import ParameterError, SymctlTypeError

try:  # POSIX only; elsewhere the folder is staged and renamed but not locked
    import fcntl
except ImportError:  # pragma: no cover
    fcntl = None

__all__ = ["OutputFolder", "check_output_folder"]

_FIGURES = "|".join(
    [
        "open_loop",
        "closed_loop",
        "delay_graph",
        "g1g3_structures",
        "nonlinear",
        "atlas_overview",
        r"simplified_A\d+",
        r"class_A\d+",
        "fit",
        r"(structure|circuit|firing)_[a-z][a-z0-9_]{0,31}",  # any circuit (the registry's names)
    ]
)
_OURS = re.compile(
    r"(results\.json|report\.md|derivation\.(tex|pdf|aux|log|out)|atlas\.(json|md|tex|pdf|aux|log|out)"
    r"|fit\.json|predictions\.csv"
    rf"|({_FIGURES})\.(pdf|png|svg))"
)
"""The names of the files an earlier run of ``symctl paper``, ``atlas``, ``derive`` or ``fit`` leaves."""
_SIGNALS = (signal.SIGINT, signal.SIGTERM)


def check_output_folder(out, argname: str = "out") -> Path:
    """``out`` as an absolute path, if a run can write its folder there; else the error.

    Parameters
    ----------
    out : str or os.PathLike
        The output folder: missing (it is made, with its parents), or an
        existing folder that is empty or holds only the files of an earlier run.
    argname : str
        The name in the messages (``"--out"`` for the command line).

    Returns
    -------
    Path
        The absolute path, symbolic links resolved.

    Raises
    ------
    SymctlTypeError
        ``out`` is not a path.
    ParameterError
        ``out`` is empty, the root, a file, a folder holding other files, or in
        a place where no folder can be made (a parent is a file, or not writable).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from symctl.report.output import check_output_folder
    >>> with tempfile.TemporaryDirectory() as parent:
    ...     check_output_folder(Path(parent) / "new").name
    'new'
    >>> check_output_folder("")
    Traceback (most recent call last):
    ...
    symctl.errors.ParameterError: out: must name a folder, got ''
    """
    if isinstance(out, bytes) or not isinstance(out, str | os.PathLike):
        raise SymctlTypeError(f"{argname}: expected a folder path (str or Path), got {out!r}")
    text = os.fspath(out)
    if not isinstance(text, str) or not text.strip():
        raise ParameterError(f"{argname}: must name a folder, got {text!r}")
    if "\0" in text:
        raise ParameterError(f"{argname}: a path cannot hold a NUL character, got {text!r}")
    try:
        path = Path(text).expanduser().resolve()
    except (OSError, RuntimeError) as exc:  # a symbolic-link loop
        raise ParameterError(f"{argname}: cannot resolve {text!r}: {exc}") from None
    if path == path.parent:
        raise ParameterError(f"{argname}: cannot replace the root folder, got {text!r}")
    if path.exists():
        if not path.is_dir():
            raise ParameterError(f"{argname}: {text!r} is a file, not a folder")
        if not os.access(path, os.W_OK | os.X_OK):
            raise ParameterError(f"{argname}: {text!r} is not writable")
        foreign = _foreign(path)
        if foreign:
            shown = ", ".join(repr(n) for n in foreign[:3]) + (", ..." if len(foreign) > 3 else "")
            raise ParameterError(
                f"{argname}: {text!r} holds files that symctl paper, derive, atlas and fit do "
                f"not write ({shown}); "
                "give a new or empty folder, or the folder of an earlier run (it is replaced)"
            )
    ancestor = path.parent
    while not ancestor.exists():
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise ParameterError(f"{argname}: cannot make {text!r}: {str(ancestor)!r} is a file")
    if not os.access(ancestor, os.W_OK | os.X_OK):
        raise ParameterError(f"{argname}: cannot make {text!r}: {str(ancestor)!r} is not writable")
    return path


def _foreign(path: Path) -> list[str]:
    """The entries of ``path`` that are not regular files an earlier run wrote."""
    with os.scandir(path) as entries:
        return sorted(
            e.name
            for e in entries
            if not (_OURS.fullmatch(e.name) and e.is_file(follow_symlinks=False))
        )


class OutputFolder:
    """A context manager that stages a folder beside ``out`` and moves it into place on success.

    Entering checks ``out`` (:func:`check_output_folder`), makes its parents,
    takes the lock ``<out>.lock``, clears what a killed run left and makes the
    staging folder; write into :attr:`staging`. Leaving without an exception
    moves the staging folder to ``out`` (replacing the old one); leaving with
    one removes it and leaves ``out`` as it was. The lock is released either way.

    Parameters
    ----------
    out : str or os.PathLike
        The output folder.
    argname : str
        The name in error messages (``"--out"`` for the command line).

    Attributes
    ----------
    out : Path
        The absolute output folder.
    staging : Path or None
        The folder being written (None outside the ``with`` block).

    Raises
    ------
    ParameterError
        As :func:`check_output_folder`; or another run holds the lock; or the
        parent cannot be made.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from symctl.report.output import OutputFolder
    >>> with tempfile.TemporaryDirectory() as parent:
    ...     try:
    ...         with OutputFolder(Path(parent) / "run") as folder:
    ...             raise RuntimeError("disk full")
    ...     except RuntimeError:
    ...         pass
    ...     list(Path(parent).iterdir())
    []
    """

    def __init__(self, out, argname: str = "out") -> None:
        self.argname = argname
        self.out = check_output_folder(out, argname)
        self.lock_path = self.out.with_name(self.out.name + ".lock")
        self.staging: Path | None = None
        self._staged: Path | None = None  # the staging folder's name, kept for final()
        self._lock_fd: int | None = None

    def __enter__(self) -> OutputFolder:
        try:
            self.out.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ParameterError(f"{self.argname}: cannot make {str(self.out)!r}: {exc}") from None
        self._lock()
        try:
            self._clear_stale()
            check_output_folder(self.out, self.argname)  # again, under the lock
            self.staging = self._staged = self._fresh("tmp")
            if self.out.is_dir():
                os.chmod(self.staging, stat.S_IMODE(self.out.stat().st_mode))
        except BaseException:
            self._unlock()
            raise
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        try:
            if exc_type is None:
                with _signals_held():
                    self._commit()
        finally:
            try:
                if self.staging is not None:
                    _remove_tree(self.staging)
                    self.staging = None
            finally:
                self._unlock()

    def final(self, paths: list[Path]) -> list[Path]:
        """``paths`` inside :attr:`staging` as they will be inside :attr:`out`."""
        return [self.out / Path(p).relative_to(self._staged) for p in paths]

    # ------------------------------------------------------------- commit
    def _commit(self) -> None:
        staging, out = self.staging, self.out
        if not out.exists():
            os.rename(staging, out)
            self.staging = None
            return
        if _exchange(staging, out):  # staging now holds the old folder
            _remove_tree(staging)
            self.staging = None
            return
        backup = self._fresh("old", make=False)
        os.rename(out, backup)
        try:
            os.rename(staging, out)
        except BaseException:
            os.rename(backup, out)
            raise
        self.staging = None
        _remove_tree(backup)

    def _fresh(self, kind: str, *, make: bool = True) -> Path:
        """A new name ``.<name>.<kind>-<hex>`` beside ``out`` (made as a folder when ``make``)."""
        while True:
            path = self.out.with_name(f".{self.out.name}.{kind}-{secrets.token_hex(4)}")
            if not make:
                if not os.path.lexists(path):
                    return path
                continue
            try:
                path.mkdir()  # mode 0o777 minus the umask, as a plain mkdir
            except FileExistsError:
                continue
            return path

    def _clear_stale(self) -> None:
        """Remove the staging and backup folders of runs that were killed (we hold the lock)."""
        prefix = f".{self.out.name}."
        stale = sorted(
            (
                p
                for p in self.out.parent.iterdir()
                if p.name.startswith(prefix)
                and re.fullmatch(r"(tmp|old)-[0-9a-f]{8}", p.name[len(prefix) :])
            ),
            key=lambda p: p.lstat().st_mtime,
        )
        backups = [p for p in stale if p.name[len(prefix) :].startswith("old-") and p.is_dir()]
        if backups and not self.out.exists():  # killed between the two renames of a commit
            os.rename(backups[-1], self.out)
            stale.remove(backups[-1])
        for p in stale:
            if p.is_symlink() or not p.is_dir():
                p.unlink(missing_ok=True)
            else:
                shutil.rmtree(p, ignore_errors=True)

    # --------------------------------------------------------------- lock
    def _lock(self) -> None:
        if fcntl is None:  # pragma: no cover
            return
        while True:
            try:
                fd = os.open(self.lock_path, os.O_RDWR | os.O_CREAT, 0o666)
            except OSError as exc:
                raise ParameterError(
                    f"{self.argname}: cannot make the lock file {str(self.lock_path)!r}: {exc}"
                ) from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = os.read(fd, 32).decode(errors="replace").strip() or "unknown"
                os.close(fd)
                raise ParameterError(
                    f"{self.argname}: {str(self.out)!r} is being written by another symctl run "
                    f"(pid {holder}, lock {self.lock_path.name!r}); wait for it to finish or "
                    "choose another folder"
                ) from None
            # the file may have been removed by the run that held it: lock the one at the path
            try:
                same = os.stat(self.lock_path).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if same:
                break
            os.close(fd)
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n".encode())
        self._lock_fd = fd

    def _unlock(self) -> None:
        fd, self._lock_fd = self._lock_fd, None
        if fd is None:
            return
        with contextlib.suppress(OSError):
            os.unlink(self.lock_path)  # while still holding it (see _lock)
        os.close(fd)


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths in one atomic step (Linux ``renameat2``); False where unsupported."""
    try:
        import ctypes

        fn = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError, ImportError):  # not glibc/Linux
        return False
    at_fdcwd, rename_exchange = -100, 2
    if fn(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False  # the kernel or the file system cannot: use the rename dance
    raise OSError(err, os.strerror(err), str(b))


@contextlib.contextmanager
def _signals_held():
    """Defer SIGINT and SIGTERM (main thread, POSIX) until the block is done."""
    mask = getattr(signal, "pthread_sigmask", None)
    if mask is None:  # pragma: no cover
        yield
        return
    old = mask(signal.SIG_BLOCK, _SIGNALS)
    try:
        yield
    finally:
        mask(signal.SIG_SETMASK, old)


def _remove_tree(path: Path, tries: int = 20) -> None:
    """Remove the folder ``path``, retrying while something still writes into it.

    A figure worker killed by a signal may have a file half written when the
    staging folder is removed (one pass of ``rmtree`` then meets a file it did
    not list, "Directory not empty"); a few passes, 50 ms apart, remove it.
    """
    for _ in range(tries):
        shutil.rmtree(path, ignore_errors=True)
        if not os.path.lexists(path):
            return
        time.sleep(0.05)
