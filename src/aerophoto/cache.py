"""A small disk cache for results that are expensive and the same for everyone (the site, the guide's stereo pair).

One call::

    site = cache.load_or_build("site", {"params": ...}, lambda: build_site(params), types=(Site, ...))

returns the value ``build()`` gives — built once, then read back from disk by every later kernel on this machine
(a Run All of chapter 07 no longer builds the site and renders the guide's pair again).

**Where.** ``$AEROPHOTO_CACHE_DIR``, else ``<state folder>/cache`` (``$AEROPHOTO_HOME/cache``, else
``~/.aerophoto/cache``): the user's own folder.  One entry per (name, key): a folder
``<name>/<key hash>/`` holding ``meta.json`` and one ``.npy`` file per array.

**The key** is the caller's ``inputs`` plus what decides the bits of the result: a fingerprint of the package's
source code (every ``.py`` file of ``aerophoto``, so an edited or upgraded package never reads an old entry),
numpy's and Python's versions, the machine and numpy's CPU features (numpy's SIMD kernels give other last bits on
another CPU: an entry is only ever read where it was computed).

**Verified before use.** An entry is read only if

* the cache is on: not when ``AEROPHOTO_CACHE=0`` (or off/no/false), not in a grading kernel
  (``AEROPHOTO_GRADING`` set: the sandbox's home is the submission's own folder, where a student could plant an
  entry), not in the browser book (its home folder is in memory);
* its folder and files belong to this user (or root) and no one else may write them (no group/other write
  bit), like ssh's rule for ``~/.ssh`` — another user cannot plant an entry in a shared or world-writable place;
* ``meta.json``'s key equals the expected key exactly, and every array file's SHA-256 equals the one recorded;
* it holds data only: arrays are read with ``allow_pickle=False`` and the structure is JSON; dataclasses are
  rebuilt only from the classes the caller names in ``types`` (no import by name, no pickle, no code).

Anything else — a missing, damaged, foreign or stale entry — is a miss: the value is built and the entry written
anew (atomically: a temporary folder renamed into place; a failed write changes nothing and is not an error).
A read entry equals the built value bit for bit (every array, dtype and frame; tests/foundation/test_cache.py).

**What it can hold**: None, bool, int, float, str, tuples, lists, dicts, numpy arrays (not of objects) and
scalars, pandas DataFrames and Series (numeric, bool and string columns) and their indexes, and instances of the
dataclasses in ``types`` (rebuilt by calling the class with their fields).  Other values raise ``TypeError``
in :func:`encode`; :func:`load_or_build` then keeps the value in memory only.

Layer 1 (foundation): imports nothing of aerophoto; the site (layer 3) and the labs (layer 4) use it.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import platform
import secrets
import shutil
import stat
import sys
from pathlib import Path

import numpy as np

__all__ = ["FORMAT", "MAX_ENTRIES", "SHIPPED", "enabled", "switched_off", "cache_dir", "code_fingerprint", "key_for",
           "encode", "decode", "load", "save", "load_or_build", "entries", "clear", "portable_key", "shipped_dir",
           "load_shipped", "write_shipped", "shipped_hits"]

#: the entry format; a change of it makes every old entry a miss
FORMAT = 1
#: entries kept per name (the oldest are removed when a new one is written)
MAX_ENTRIES = 8
_PKG = Path(__file__).resolve().parent
_OFF = ("0", "off", "no", "false")
#: the browser book's read-only entries: a package of data only, made when the site is built
#: (:func:`aerophoto.lite.shipped_wheel`) and loaded with the book; see :func:`load_shipped`
SHIPPED = "aerophoto_shipped"
_SHIPPED_HITS: list = []


# =========================================================================== where, and whether
def switched_off() -> bool:
    """``AEROPHOTO_CACHE=0`` (or off/no/false), or a grading kernel: no entry is read, shipped or not — of this
    cache or of the report's signed one (:func:`aerophoto.diskcache.enabled`)."""
    return (os.environ.get("AEROPHOTO_CACHE", "1").strip().lower() in _OFF
            or bool(os.environ.get("AEROPHOTO_GRADING")))


def enabled() -> bool:
    """Whether the cache is on in this process (see the module notes)."""
    return not switched_off() and sys.platform != "emscripten"


def cache_dir() -> Path:
    """The cache's folder: ``$AEROPHOTO_CACHE_DIR``, else ``$AEROPHOTO_HOME/cache``, else ``~/.aerophoto/cache``."""
    env = os.environ.get("AEROPHOTO_CACHE_DIR", "").strip()
    if env:
        return Path(env).expanduser()
    home = os.environ.get("AEROPHOTO_HOME", "").strip()
    return (Path(home).expanduser() if home else Path.home() / ".aerophoto") / "cache"


def _trusted(path: Path) -> bool:
    """``path`` belongs to this user (or root) and nobody else may write it."""
    if not hasattr(os, "getuid"):  # pragma: no cover - Windows: no owners to compare
        return True
    try:
        st = path.lstat()
    except OSError:
        return False
    if stat.S_ISLNK(st.st_mode):
        return False
    return st.st_uid in (os.getuid(), 0) and not st.st_mode & (stat.S_IWGRP | stat.S_IWOTH)


# =========================================================================== the key
_FINGERPRINT: list = []


def code_fingerprint() -> str:
    """SHA-256 over the package's source files (their paths and bytes), computed once per process."""
    if not _FINGERPRINT:
        h = hashlib.sha256()
        for p in sorted(_PKG.rglob("*.py")):
            if "__pycache__" in p.parts:
                continue
            h.update(p.relative_to(_PKG).as_posix().encode())
            h.update(b"\0")
            h.update(p.read_bytes())
            h.update(b"\0")
        _FINGERPRINT.append(h.hexdigest())
    return _FINGERPRINT[0]


def _cpu_features() -> str:
    try:
        from numpy._core._multiarray_umath import __cpu_features__ as feats
    except ImportError:  # pragma: no cover - numpy < 2
        from numpy.core._multiarray_umath import __cpu_features__ as feats
    return ",".join(sorted(k for k, on in feats.items() if on))


def key_for(name: str, inputs) -> dict:
    """The whole key of an entry: ``name``, the caller's ``inputs`` (JSON-able) and what decides the bits."""
    return {"format": FORMAT, "name": str(name), "inputs": json.loads(json.dumps(inputs, sort_keys=True)),
            "code": code_fingerprint(), "numpy": np.__version__, "python": platform.python_version(),
            "machine": platform.machine(), "cpu": hashlib.sha256(_cpu_features().encode()).hexdigest()[:16]}


def _key_hash(key: dict) -> str:
    return hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:32]


# =========================================================================== values ↔ JSON + arrays
def encode(value, arrays: list, types: tuple = ()):
    """``value`` as a JSON-able tree; its arrays are appended to ``arrays`` and named by their index."""
    import pandas as pd

    def enc(x):
        if x is None or isinstance(x, (bool, str)) or type(x) in (int, float):
            return x
        if isinstance(x, np.generic):
            if x.dtype.kind not in "biufc":
                raise TypeError(f"cannot cache a numpy scalar of dtype {x.dtype}")
            return {"__scalar__": x.dtype.str, "v": enc(x.item())}
        if isinstance(x, np.ndarray):
            if x.dtype.hasobject:
                raise TypeError("cannot cache an array of Python objects")
            arrays.append(np.ascontiguousarray(x))
            return {"__array__": len(arrays) - 1, "writeable": bool(x.flags.writeable)}
        if isinstance(x, tuple):
            return {"__tuple__": [enc(v) for v in x]}
        if isinstance(x, list):
            return [enc(v) for v in x]
        if isinstance(x, dict):
            return {"__dict__": [[enc(k), enc(v)] for k, v in x.items()]}
        if isinstance(x, pd.DataFrame):
            return {"__frame__": [[enc(c), _enc_column(x[c], enc)] for c in x.columns], "index": _enc_index(x.index, enc)}
        if isinstance(x, pd.Series):
            return {"__series__": _enc_column(x, enc), "name": enc(x.name), "index": _enc_index(x.index, enc)}
        if dataclasses.is_dataclass(x) and type(x) in types:
            fields = {f.name: enc(getattr(x, f.name)) for f in dataclasses.fields(x) if f.init}
            return {"__dataclass__": type(x).__qualname__, "fields": fields}
        raise TypeError(f"cannot cache a value of type {type(x).__module__}.{type(x).__qualname__}")

    return enc(value)


def _enc_column(s, enc):
    if isinstance(s.dtype, np.dtype) and s.dtype.kind in "biufcmM":
        return {"values": enc(s.to_numpy()), "dtype": str(s.dtype)}
    if s.dtype.kind in "OU" or str(s.dtype) in ("str", "string"):
        vals = [None if v is None or (isinstance(v, float) and v != v) else v for v in s.tolist()]
        if not all(v is None or isinstance(v, str) for v in vals):
            raise TypeError(f"cannot cache column {s.name!r}: it holds other objects than strings")
        return {"strings": vals, "dtype": str(s.dtype)}
    raise TypeError(f"cannot cache a column of dtype {s.dtype}")


def _enc_index(ix, enc):
    import pandas as pd

    if isinstance(ix, pd.RangeIndex):
        return {"range": [ix.start, ix.stop, ix.step], "name": enc(ix.name)}
    if isinstance(ix, pd.MultiIndex):
        raise TypeError("cannot cache a MultiIndex")
    return {"column": _enc_column(ix.to_series(), enc), "name": enc(ix.name)}


def decode(tree, arrays, types: tuple = ()):
    """The value :func:`encode` made ``tree`` of (``arrays``: the arrays in order; ``types``: the dataclasses)."""
    import pandas as pd

    by_name = {t.__qualname__: t for t in types}

    def column(c):
        if "values" in c:
            return pd.Series(dec(c["values"]), dtype=c["dtype"] if c["dtype"] != "object" else None)
        return pd.Series(pd.array(c["strings"], dtype=c["dtype"]))

    def index(ix):
        if "range" in ix:
            return pd.RangeIndex(*ix["range"], name=dec(ix["name"]))
        return pd.Index(column(ix["column"]), name=dec(ix["name"]))

    def dec(x):
        if isinstance(x, list):
            return [dec(v) for v in x]
        if not isinstance(x, dict):
            return x
        if "__array__" in x:
            a = arrays[x["__array__"]]
            a.flags.writeable = bool(x["writeable"])
            return a
        if "__scalar__" in x:
            return np.dtype(x["__scalar__"]).type(dec(x["v"]))
        if "__tuple__" in x:
            return tuple(dec(v) for v in x["__tuple__"])
        if "__dict__" in x:
            return {dec(k): dec(v) for k, v in x["__dict__"]}
        if "__frame__" in x:
            ix = index(x["index"])
            cols = {}
            for name, c in x["__frame__"]:
                s = column(c)
                s.index = ix
                cols[dec(name)] = s
            return pd.DataFrame(cols, index=ix)
        if "__series__" in x:
            s = column(x["__series__"])
            s.index = index(x["index"])
            s.name = dec(x["name"])
            return s
        if "__dataclass__" in x:
            cls = by_name.get(x["__dataclass__"])
            if cls is None:
                raise ValueError(f"the entry names a dataclass {x['__dataclass__']!r} that was not allowed")
            return cls(**{k: dec(v) for k, v in x["fields"].items()})
        raise ValueError(f"not an encoded value: keys {sorted(x)}")

    return dec(tree)


# =========================================================================== entries on disk
def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _entry_dir(key: dict) -> Path:
    return cache_dir() / key["name"] / _key_hash(key)


def load(key: dict, types: tuple = ()):
    """``(value,)`` of the entry ``key`` (:func:`key_for`) if it passes every check of the module notes, else None
    (a miss; the tuple tells a cached None from a miss)."""
    if not enabled():
        return None
    root = cache_dir()
    d = _entry_dir(key)
    if not all(_trusted(p) for p in (root, d.parent, d)):
        return None
    return _read_entry(d, key, types, _trusted)


def _read_entry(d: Path, key: dict, types: tuple, trusted=lambda _p: True):
    """``(value,)`` of the entry folder ``d`` when its ``meta.json`` carries exactly ``key``, every file passes
    ``trusted`` and every array file its recorded SHA-256; else None.  Data only (``allow_pickle=False``)."""
    try:
        meta_path = d / "meta.json"
        if not trusted(meta_path):
            return None
        meta = json.loads(meta_path.read_text(encoding="utf-8"))
        if meta.get("key") != key:
            return None
        arrays = []
        for i, (fname, digest) in enumerate(meta["files"]):
            p = d / fname
            if fname != f"a{i}.npy" or not trusted(p) or _sha256(p) != digest:
                return None
            arrays.append(np.load(p, allow_pickle=False))
        return (decode(meta["tree"], arrays, types),)
    except (OSError, ValueError, KeyError, TypeError):
        return None


def save(key: dict, value, types: tuple = ()) -> bool:
    """Write ``value`` as the entry ``key``; True when written (False: the cache is off, the value cannot be
    cached, or the folder cannot be written — never an error)."""
    if not enabled():
        return False
    arrays: list = []
    try:
        tree = encode(value, arrays, types)
    except TypeError:
        return False
    root = cache_dir()
    try:
        root.mkdir(parents=True, exist_ok=True, mode=0o700)
        if not _trusted(root):
            return False
        parent = root / key["name"]
        parent.mkdir(exist_ok=True, mode=0o700)
        final = _write_entry(parent, key, arrays, tree, lambda: load(key, types) is not None)
        _prune(parent, keep=final.name)
        return True
    except (OSError, ValueError):
        return False


def _write_entry(parent: Path, key: dict, arrays: list, tree, exists_ok, extra: dict | None = None) -> Path:
    """Write one entry under ``parent`` atomically (a temporary folder renamed into place); ``exists_ok()`` says
    whether an entry already there is good (then it is kept); ``extra``: more fields of its ``meta.json``."""
    tmp = parent / f".tmp-{secrets.token_hex(8)}"
    tmp.mkdir(mode=0o700)
    try:
        files = []
        for i, a in enumerate(arrays):
            p = tmp / f"a{i}.npy"
            np.save(p, a, allow_pickle=False)
            files.append([p.name, _sha256(p)])
        meta = {"key": key, "files": files, "tree": tree, **(extra or {})}
        (tmp / "meta.json").write_text(json.dumps(meta), encoding="utf-8")
        final = parent / _key_hash(key)
        if final.exists():
            if exists_ok():  # another process wrote it meanwhile: keep theirs
                return final
            shutil.rmtree(final, ignore_errors=True)  # a damaged or foreign entry: replaced
        os.rename(tmp, final)
        return final
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def _prune(parent: Path, keep: str) -> None:
    """At most :data:`MAX_ENTRIES` entries under ``parent``; entries of another code fingerprint go first."""
    here = code_fingerprint()
    found = []
    for d in parent.iterdir():
        if d.name == keep or d.name.startswith(".") or not d.is_dir():
            continue
        try:
            code = json.loads((d / "meta.json").read_text(encoding="utf-8"))["key"]["code"]
        except (OSError, ValueError, KeyError, TypeError):
            code = None
        if code != here:
            shutil.rmtree(d, ignore_errors=True)
        else:
            found.append((d.stat().st_mtime, d))
    for _, d in sorted(found, reverse=True)[MAX_ENTRIES - 1:]:
        shutil.rmtree(d, ignore_errors=True)


def load_or_build(name: str, inputs, build, *, types: tuple = ()):
    """The value ``build()`` gives for ``inputs``: read from the cache when a verified entry exists, else built
    (and written for the next time).  ``inputs`` must be JSON-able and name everything the value depends on
    besides the package's code; ``types``: the dataclasses the value may contain."""
    key = key_for(name, inputs)
    hit = load(key, types)
    if hit is None and sys.platform == "emscripten":  # the browser book: no disk of its own, the site's entries
        hit = load_shipped(name, inputs, types)
    if hit is not None:
        return hit[0]
    value = build()
    save(key, value, types)
    return value


def entries(name: str | None = None) -> list:
    """The entries on disk (folders), all or of one ``name``."""
    root = cache_dir()
    if not root.is_dir():
        return []
    parents = [root / name] if name else [p for p in root.iterdir() if p.is_dir()]
    return sorted(d for p in parents if p.is_dir() for d in p.iterdir() if d.is_dir() and not d.name.startswith("."))


def clear() -> None:
    """Remove every entry of both halves of the cache: the chapters' folders and the report's signed files
    (:meth:`aerophoto.diskcache.Cache.clear`).  The folder and the report's secret key stay."""
    from . import diskcache  # imported here: diskcache builds on this module

    for d in entries():
        shutil.rmtree(d, ignore_errors=True)
    diskcache.Cache(cache_dir()).clear()


# =========================================================================== the browser book's shipped entries
def portable_key(name: str, inputs) -> dict:
    """The key of a shipped entry: :func:`key_for` without the interpreter and the machine — the entry was computed
    on the machine that built the site (recorded in its ``made_on``), with this very source code."""
    key = key_for(name, inputs)
    return {k: key[k] for k in ("format", "name", "inputs", "code")}


def shipped_dir() -> Path | None:
    """The folder of the shipped entries (the package :data:`SHIPPED`), or None where it is not installed."""
    import importlib.util

    spec = importlib.util.find_spec(SHIPPED)
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(list(spec.submodule_search_locations)[0])


def load_shipped(name: str, inputs, types: tuple = ()):
    """``(value,)`` of the shipped entry for ``(name, inputs)``, else None.

    Used only in the browser book (:func:`load_or_build` there; the browser has no disk the cache could keep, and
    every visitor would rebuild the same site — about 5 s of WebAssembly in most chapters).  The entry must carry
    exactly :func:`portable_key` (the same package source, byte for byte) and every array file its recorded
    SHA-256; it is data only (``allow_pickle=False``, dataclasses from ``types``).  Never in a grading kernel or
    with the cache switched off.
    """
    if switched_off():
        return None
    root = shipped_dir()
    if root is None:
        return None
    key = portable_key(name, inputs)
    hit = _read_entry(root / key["name"] / _key_hash(key), key, types)
    if hit is not None:
        _SHIPPED_HITS.append(key["name"])
    return hit


def write_shipped(dest: Path, name: str, inputs, value, types: tuple = ()) -> Path:
    """Write ``value`` as the shipped entry for ``(name, inputs)`` under ``dest`` (the site's build); returns
    its folder.  Raises ``TypeError`` for a value the cache cannot hold."""
    arrays: list = []
    tree = encode(value, arrays, types)
    key = portable_key(name, inputs)
    parent = Path(dest) / key["name"]
    parent.mkdir(parents=True, exist_ok=True)
    made_on = {"python": platform.python_version(), "numpy": np.__version__, "machine": platform.machine()}
    return _write_entry(parent, key, arrays, tree, lambda: False, {"made_on": made_on})


def shipped_hits() -> list:
    """The names of the shipped entries read in this process, in order (the browser book's tests ask)."""
    return list(_SHIPPED_HITS)
