r"""An output folder written all at once: staged in ``.<name>.tmp-<hex>`` beside ``out`` under the
lock ``<out>.lock``, then renamed into place with :func:`os.replace`, so ``out`` is always the old
complete folder or the new complete one (docs/reliability.md gives what each failure leaves)."""

from __future__ import annotations

import contextlib
import json
import os
import re
import secrets
import shutil
import stat
from pathlib import Path

from symctl.errors import ParameterError, SymctlTypeError

try:  # POSIX only; elsewhere the folder is staged and renamed but not locked
    import fcntl
except ImportError:  # pragma: no cover
    fcntl = None

__all__ = ["OutputFolder", "check_output_folder", "write_json"]

_FIGURES = (
    r"open_loop|closed_loop|delay_graph|g1g3_structures|nonlinear|fit|spiking_cost"
    r"|atlas_(overview|conjectured)|simplified_A\d+|class_A\d+"
    r"|(structure|circuit|firing)_[a-z][a-z0-9_]{0,31}"  # any circuit (the registry's names)
)
_OURS = re.compile(  # the files of an earlier run of symctl paper, atlas, derive, fit, spiking
    r"(results\.json|report\.md|derivation\.(tex|pdf|aux|log|out)|atlas\.(json|md|tex|pdf|aux|log|out)"
    r"|fit\.json|predictions\.csv|spiking\.(json|md)"
    rf"|({_FIGURES})\.(pdf|png|svg))"
)


def check_output_folder(out, argname: str = "out") -> Path:
    """``out`` as an absolute path (links resolved) if a run can write its folder there: a missing
    folder, or one holding nothing but the files of an earlier run.

    SymctlTypeError when ``out`` is not a path; ParameterError (naming ``argname``) when it is
    empty, the root, a file, a folder holding other files, or where no folder can be made."""
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
    """Stage a folder beside ``out`` and rename it into place on success.

    Entering checks ``out`` (:func:`check_output_folder`), makes its parents, takes the lock (a
    ParameterError when another run holds it), clears what a killed run left and makes
    :attr:`staging`. Leaving without an exception renames :attr:`staging` to ``out``; with one,
    removes it and leaves ``out`` as it was."""

    def __init__(self, out, argname: str = "out") -> None:
        self.argname = argname
        self.out = check_output_folder(out, argname)
        self.lock_path = self.out.with_name(self.out.name + ".lock")
        self.staging: Path | None = None
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
            self.staging = self._sibling("tmp")
            self.staging.mkdir()  # mode 0o777 minus the umask, as a plain mkdir
            if self.out.is_dir():
                os.chmod(self.staging, stat.S_IMODE(self.out.stat().st_mode))
        except BaseException:
            self._unlock()
            raise
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        old = self._sibling("old") if self.out.exists() else None
        try:
            if exc_type is None:
                if old is not None:
                    os.replace(self.out, old)
                os.replace(self.staging, self.out)
        finally:
            try:
                if old is not None and os.path.lexists(old) and not os.path.lexists(self.out):
                    os.replace(old, self.out)  # stopped between the renames: the old one back
                for path in (self.staging, old):  # the staging folder unless it is out now
                    if path is not None and os.path.lexists(path):
                        shutil.rmtree(path, ignore_errors=True)
            finally:
                self._unlock()

    def final(self, paths: list[Path]) -> list[Path]:
        """``paths`` inside :attr:`staging` as they are inside :attr:`out` once renamed."""
        return [self.out / Path(p).relative_to(self.staging) for p in paths]

    def _sibling(self, kind: str) -> Path:
        """A free name ``.<name>.<kind>-<hex>`` beside ``out``."""
        while True:
            path = self.out.with_name(f".{self.out.name}.{kind}-{secrets.token_hex(4)}")
            if not os.path.lexists(path):
                return path

    def _clear_stale(self) -> None:
        """Remove what killed runs left, restoring ``out`` from a backup when it is missing."""
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
        if backups and not self.out.exists():  # killed between the two renames
            os.replace(backups[-1], self.out)
            stale.remove(backups[-1])
        for p in stale:
            if p.is_symlink() or not p.is_dir():
                p.unlink(missing_ok=True)
            else:
                shutil.rmtree(p, ignore_errors=True)

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
            try:  # the run that held it may have removed the file: lock the one at the path
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


def write_json(path: Path, value, *, indent: int = 2, allow_nan: bool = True) -> Path:
    """Write ``value`` to ``path`` as JSON ending in a newline; returns the path."""
    path.write_text(json.dumps(value, indent=indent, allow_nan=allow_nan) + "\n", encoding="utf-8")
    return path
