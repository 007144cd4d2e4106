"""A verified disk cache for results that are slow to rebuild, for the student's own machine only.

What it stores is plain data — bytes, JSON, or numpy arrays (``.npz`` read with ``allow_pickle=False``) — so
reading an entry never runs code.  Every entry is signed: an HMAC-SHA256 of its key and content under a
secret key that only this machine's user can read (``<folder>/key``, 32 random bytes, mode 0600), stored
beside it and checked before the entry is used.  An entry written by anyone without that key (copied in,
edited, truncated, left by another package version) fails the check and is rebuilt; the failure is counted
(:attr:`Cache.stats`), never raised.

Keys are JSON-able mappings, completed by the chapters' cache's own rule (:func:`aerophoto.cache.key_for`: a
SHA-256 of the package's source files, numpy's and Python's versions, the machine and its CPU features), so an
entry never outlives the code that computed it and is never read on another machine.

**Off unless asked for.**  Nothing reads or writes the cache unless the caller opens it with
:func:`enabled` (a context manager; the setting is a :mod:`contextvars` variable, so it holds for that
call's thread and context only).  The student's report (:mod:`aerophoto.report`) opens it; the instructor's
grading (:mod:`aerophoto.course`) never does, so a grade is never computed from anything a student's machine
left on disk.  Code that wants a cached value asks :func:`active` and computes it directly when it is None::

    from aerophoto import diskcache
    with diskcache.enabled():                       # the report, on the student's machine
        c = diskcache.active()
        arrays = c.arrays("site", {"i": 57}, lambda: build_site_arrays(57))

This is the report's half of the book's one disk cache (:mod:`aerophoto.cache` is the chapters' half): the same
folder (:func:`aerophoto.cache.cache_dir`: ``$AEROPHOTO_CACHE_DIR``, else ``$AEROPHOTO_HOME/cache``, else
``~/.aerophoto/cache``, beside ``student.json``), the same key, the same switch — ``AEROPHOTO_CACHE=0`` (or off,
no, false) and a grading kernel (``AEROPHOTO_GRADING`` set) keep it off even inside :func:`enabled`
(:func:`aerophoto.cache.switched_off`) — and the same :func:`aerophoto.cache.clear`.  The two differ in what they
trust: the chapters' entries are the same for everyone and are checked by owner and hash; the report's hold a
student's own work and are signed.  Layer 1 (foundation): the standard library, numpy and :mod:`aerophoto.cache`.
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

from . import cache as _cache

__all__ = ["Cache", "enabled", "active", "canonical_key", "MAX_ENTRY_BYTES"]

#: an entry larger than this is neither written nor read (a rendered sheet of photos is ~30 MB)
MAX_ENTRY_BYTES = 200_000_000
_KEY_BYTES = 32
_ACTIVE: contextvars.ContextVar = contextvars.ContextVar("aerophoto_diskcache", default=None)


def canonical_key(namespace: str, key) -> str:
    """The entry's key as canonical JSON text (sorted keys, no spaces): :func:`aerophoto.cache.key_for`'s key —
    the namespace, ``key``, the package's source fingerprint, numpy's and Python's versions, the machine and its CPU
    features — the same key the chapters' cache uses.

    Raises ValueError naming ``key`` when it is not plain JSON data (a float NaN, an object).
    """
    if not isinstance(namespace, str) or not namespace.replace("-", "").replace("_", "").isalnum():
        raise ValueError(f"namespace = {namespace!r}: expected a short name of letters, digits, '-' and '_'")
    try:
        return json.dumps(_cache.key_for(namespace, key), sort_keys=True, separators=(",", ":"), ensure_ascii=True,
                          allow_nan=False)
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

    def clear(self) -> int:
        """Remove every entry (``<2 hex digits>/<hash>.data`` and ``.sig``); the secret key stays.  The count of
        files removed.  :func:`aerophoto.cache.clear` calls it for the book's one cache folder."""
        n = 0
        if not self.folder.is_dir():
            return n
        for sub in self.folder.iterdir():
            if sub.is_dir() and len(sub.name) == 2 and all(c in "0123456789abcdef" for c in sub.name):
                for f in sub.iterdir():
                    if f.suffix in (".data", ".sig") and f.is_file():
                        f.unlink(missing_ok=True)
                        n += 1
        return n

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

    ``folder``: default :func:`aerophoto.cache.cache_dir` (one folder for both caches).  A folder that cannot be used (read-only, a key with the wrong
    owner or mode) leaves the cache off, so the caller computes everything as without it; so do
    ``AEROPHOTO_CACHE=0`` and a grading kernel.
    """
    cache = None if _cache.switched_off() else Cache(Path(folder) if folder is not None else _cache.cache_dir())
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
