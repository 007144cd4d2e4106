"""A verified disk cache for results that are slow to rebuild, for the student's own machine only.

What it stores is plain data — bytes, JSON, or numpy arrays (``.npz`` read with ``allow_pickle=False``) — so
reading an entry never runs code.  Every entry is signed: an HMAC-SHA256 of its key and content under a
secret key that only this machine's user can read (``<folder>/key``, 32 random bytes, mode 0600), stored
beside it and checked before the entry is used.  An entry written by anyone without that key (copied in,
edited, truncated, left by another package version) fails the check and is rebuilt; the failure is counted
(:attr:`Cache.stats`), never raised.

Keys are JSON-able mappings; the cache adds :func:`code_fingerprint` — the package version and a cheap
fingerprint of its source files (path, size and modification time of every ``.py`` file of the installed
package) — so an entry never outlives the code that computed it.

**Off unless asked for.**  Nothing reads or writes the cache unless the caller opens it with
:func:`enabled` (a context manager; the setting is a :mod:`contextvars` variable, so it holds for that
call's thread and context only).  The student's report (:mod:`aerophoto.report`) opens it; the instructor's
grading (:mod:`aerophoto.course`) never does, so a grade is never computed from anything a student's machine
left on disk.  Code that wants a cached value asks :func:`active` and computes it directly when it is None::

    from aerophoto import diskcache
    with diskcache.enabled():                       # the report, on the student's machine
        c = diskcache.active()
        arrays = c.arrays("site", {"i": 57}, lambda: build_site_arrays(57))

Where: ``$AEROPHOTO_CACHE_DIR`` if set, else ``<state dir>/cache`` (``$AEROPHOTO_HOME`` or ``~/.aerophoto``, the
folder that already holds ``student.json``).  ``AEROPHOTO_CACHE=0`` (or off, no, false) and a grading kernel
(``AEROPHOTO_GRADING`` set) keep it off even inside :func:`enabled`.  Layer 1 (foundation): the standard library
and numpy only.
"""

from __future__ import annotations

import contextlib
import contextvars
import hashlib
import hmac
import io
import json
import os
import secrets
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Cache", "enabled", "active", "default_folder", "code_fingerprint", "canonical_key", "MAX_ENTRY_BYTES"]

#: an entry larger than this is neither written nor read (a rendered sheet of photos is ~30 MB)
MAX_ENTRY_BYTES = 200_000_000
_KEY_BYTES = 32
_ACTIVE: contextvars.ContextVar = contextvars.ContextVar("aerophoto_diskcache", default=None)
_FINGERPRINT: list = []


def default_folder() -> Path:
    """``$AEROPHOTO_CACHE_DIR``, else ``$AEROPHOTO_HOME/cache``, else ``~/.aerophoto/cache``."""
    env = os.environ.get("AEROPHOTO_CACHE_DIR", "").strip()
    if env:
        return Path(env).expanduser()
    home = os.environ.get("AEROPHOTO_HOME", "").strip()
    return (Path(home).expanduser() if home else Path.home() / ".aerophoto") / "cache"


def code_fingerprint() -> str:
    """The package version, Python's and numpy's versions, the machine, and a hash of (path, size, mtime) of every
    ``.py`` file of the package (once per process): an entry is read only by the code and the machine that wrote it."""
    if not _FINGERPRINT:
        import platform

        import numpy as np

        from . import __version__

        root = Path(__file__).resolve().parent
        h = hashlib.sha256(f"{__version__}|{platform.python_version()}|{np.__version__}|{platform.machine()}".encode())
        for p in sorted(root.rglob("*.py")):
            if "__pycache__" in p.parts:
                continue
            st = p.stat()
            h.update(f"{p.relative_to(root)}\0{st.st_size}\0{st.st_mtime_ns}\n".encode())
        _FINGERPRINT.append(f"{__version__}+{h.hexdigest()[:20]}")
    return _FINGERPRINT[0]


def canonical_key(namespace: str, key) -> str:
    """The entry's key as canonical JSON text (sorted keys, no spaces), code fingerprint included.

    Raises ValueError naming ``key`` when it is not plain JSON data (a float NaN, an object).
    """
    if not isinstance(namespace, str) or not namespace.replace("-", "").replace("_", "").isalnum():
        raise ValueError(f"namespace = {namespace!r}: expected a short name of letters, digits, '-' and '_'")
    try:
        return json.dumps({"code": code_fingerprint(), "ns": namespace, "key": key}, sort_keys=True,
                          separators=(",", ":"), ensure_ascii=True, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"key = {key!r} is not plain JSON data ({exc})") from None


@dataclass
class Cache:
    """A folder of signed entries (see the module notes).  ``stats``: hits, misses, rejected, written."""

    folder: Path
    stats: dict = field(default_factory=lambda: {"hits": 0, "misses": 0, "rejected": 0, "written": 0})

    def __post_init__(self):
        self.folder = Path(self.folder)
        self._secret: bytes | None = None

    # ---- the secret key
    def _key(self) -> bytes:
        if self._secret is None:
            self.folder.mkdir(parents=True, exist_ok=True, mode=0o700)
            path = self.folder / "key"
            if not path.exists():
                fd, tmp = tempfile.mkstemp(dir=self.folder, prefix=".key-")
                try:
                    os.chmod(tmp, 0o600)
                    os.write(fd, secrets.token_bytes(_KEY_BYTES))
                finally:
                    os.close(fd)
                with contextlib.suppress(FileExistsError):
                    os.link(tmp, path)  # never replaces a key another process wrote first
                os.unlink(tmp)
            st = path.stat()
            if st.st_mode & 0o077 or (hasattr(os, "getuid") and st.st_uid != os.getuid()):
                raise PermissionError(f"{path} must belong to this user and be readable by nobody else (mode 0600)")
            secret = path.read_bytes()
            if len(secret) != _KEY_BYTES:
                raise PermissionError(f"{path} is not a key of this cache ({len(secret)} bytes)")
            self._secret = secret
        return self._secret

    def _paths(self, text: str) -> tuple[Path, Path]:
        name = hashlib.sha256(text.encode()).hexdigest()
        sub = self.folder / name[:2]
        return sub / f"{name}.data", sub / f"{name}.sig"

    def _sign(self, text: str, data: bytes) -> str:
        return hmac.new(self._key(), text.encode() + b"\0" + data, hashlib.sha256).hexdigest()

    # ---- bytes: the one primitive
    def get_bytes(self, namespace: str, key) -> bytes | None:
        """The entry's bytes if present and its signature holds, else None (counted as a miss or a rejection)."""
        text = canonical_key(namespace, key)
        data_path, sig_path = self._paths(text)
        try:
            if data_path.stat().st_size > MAX_ENTRY_BYTES:
                raise OSError("too large")
            data = data_path.read_bytes()
            sig = sig_path.read_text(encoding="ascii").strip()
        except (OSError, UnicodeDecodeError):
            self.stats["misses"] += 1
            return None
        if not hmac.compare_digest(sig, self._sign(text, data)):
            self.stats["rejected"] += 1
            return None
        self.stats["hits"] += 1
        return data

    def put_bytes(self, namespace: str, key, data: bytes) -> None:
        """Write an entry (atomically: a reader sees the old entry, the new one, or none)."""
        data = bytes(data)
        if len(data) > MAX_ENTRY_BYTES:
            return
        text = canonical_key(namespace, key)
        data_path, sig_path = self._paths(text)
        data_path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        sig = self._sign(text, data)
        for path, payload in ((data_path, data), (sig_path, sig.encode("ascii"))):
            fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
            try:
                with os.fdopen(fd, "wb") as fh:
                    fh.write(payload)
                os.replace(tmp, path)
            except BaseException:
                with contextlib.suppress(OSError):
                    os.unlink(tmp)
                raise
        self.stats["written"] += 1

    def blob(self, namespace: str, key, build) -> bytes:
        """The cached bytes of ``key``, or ``build()`` (bytes) written and returned."""
        data = self.get_bytes(namespace, key)
        if data is None:
            data = bytes(build())
            self.put_bytes(namespace, key, data)
        return data

    # ---- JSON and arrays, on top of bytes
    def json(self, namespace: str, key, build):
        """The cached JSON value of ``key``, or ``build()`` (plain JSON data, no NaN) written and returned."""
        data = self.get_bytes(namespace, key)
        if data is not None:
            try:
                return json.loads(data.decode("utf-8"))
            except (UnicodeDecodeError, ValueError):
                self.stats["rejected"] += 1
        value = build()
        self.put_bytes(namespace, key, json.dumps(value, sort_keys=True, allow_nan=False).encode("utf-8"))
        return value

    def arrays(self, namespace: str, key, build) -> dict:
        """The cached ``{name: numpy array}`` of ``key`` (no object arrays), or ``build()`` written and returned."""
        import numpy as np

        data = self.get_bytes(namespace, key)
        if data is not None:
            try:
                with np.load(io.BytesIO(data), allow_pickle=False) as z:
                    return {k: z[k] for k in z.files}
            except (ValueError, OSError, EOFError):
                self.stats["rejected"] += 1
        value = {str(k): np.asarray(a) for k, a in build().items()}
        if any(a.dtype == object for a in value.values()):
            raise ValueError("build: an object array cannot be cached (only numbers, booleans and text)")
        buf = io.BytesIO()
        np.savez_compressed(buf, **value)
        self.put_bytes(namespace, key, buf.getvalue())
        return value


@contextlib.contextmanager
def enabled(folder=None):
    """Open the cache for this context (the student's machine): :func:`active` returns it inside the block.

    ``folder``: default :func:`default_folder`.  A folder that cannot be used (read-only, a key with the wrong
    owner or mode) leaves the cache off, so the caller computes everything as without it; so do
    ``AEROPHOTO_CACHE=0`` and a grading kernel.
    """
    off = os.environ.get("AEROPHOTO_CACHE", "").strip().lower() in ("0", "off", "no", "false") \
        or bool(os.environ.get("AEROPHOTO_GRADING"))
    cache = None if off else Cache(Path(folder) if folder is not None else default_folder())
    if cache is not None:
        try:
            cache._key()
        except OSError:
            cache = None
    token = _ACTIVE.set(cache)
    try:
        yield cache
    finally:
        _ACTIVE.reset(token)


def active() -> Cache | None:
    """The cache opened by the innermost :func:`enabled` of this context, or None (the default: no cache)."""
    return _ACTIVE.get()
