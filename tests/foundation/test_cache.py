"""aerophoto.cache: a read entry equals the built value bit for bit, and an entry is read only when it is verified."""

from __future__ import annotations

import dataclasses
import json
import os

import numpy as np
import pandas as pd
import pytest

from aerophoto import cache


@dataclasses.dataclass(frozen=True)
class Thing:
    a: np.ndarray
    label: str
    inner: tuple = ()


@dataclasses.dataclass(frozen=True)
class Other:
    x: int


@pytest.fixture
def cdir(tmp_path, monkeypatch):
    d = tmp_path / "cache"
    monkeypatch.setenv("AEROPHOTO_CACHE_DIR", str(d))
    monkeypatch.delenv("AEROPHOTO_GRADING", raising=False)
    monkeypatch.setenv("AEROPHOTO_CACHE", "1")
    return d


def _value():
    ro = np.arange(12, dtype=np.uint8).reshape(3, 4)
    ro.flags.writeable = False
    frame = pd.DataFrame({"id": np.array([3, 1, 2]), "kind": pd.array(["a", None, "c"], dtype="str"),
                          "X_m": [1.5, np.nan, -0.0], "ok": [True, False, True]})
    named = pd.DataFrame({"v": [1.0, 2.0]}, index=pd.Index(["p", "q"], name="point"))
    return {"f64": np.linspace(0, 1, 7), "f32": np.float32([1e-8, np.inf]), "ro": ro, "bools": np.eye(3, dtype=bool),
            "frame": frame, "named": named, "series": pd.Series([1.0, 2.0], index=pd.RangeIndex(5, 7), name="s"),
            "scalars": (np.float64(0.1), np.int64(-3), np.bool_(True), 0.1 + 0.2, 7, None, "ж", float("nan")),
            (1, "k"): [Thing(np.zeros(2), "t", (Thing(np.ones(1), "u"),))], 4: {"nested": [1, [2, 3.5]]}}


def _same(a, b):
    assert type(a) is type(b), (type(a), type(b))
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape and a.flags.writeable == b.flags.writeable
        assert np.array_equal(a, b, equal_nan=a.dtype.kind in "fc")
    elif isinstance(a, pd.DataFrame):
        pd.testing.assert_frame_equal(a, b, check_exact=True)
    elif isinstance(a, pd.Series):
        pd.testing.assert_series_equal(a, b, check_exact=True)
    elif isinstance(a, dict):
        assert list(a) == list(b)
        for k in a:
            _same(a[k], b[k])
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _same(x, y)
    elif dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            _same(getattr(a, f.name), getattr(b, f.name))
    elif isinstance(a, float) and a != a:
        assert b != b
    else:
        assert a == b and repr(a) == repr(b)


def test_an_entry_reads_back_what_was_built_and_build_runs_once(cdir):
    calls = []

    def build():
        calls.append(1)
        return _value()

    first = cache.load_or_build("thing", {"n": 1}, build, types=(Thing,))
    again = cache.load_or_build("thing", {"n": 1}, build, types=(Thing,))
    assert len(calls) == 1
    _same(first, _value())
    _same(again, first)
    assert len(cache.entries("thing")) == 1
    cache.load_or_build("thing", {"n": 2}, build, types=(Thing,))  # other inputs: another entry
    assert len(calls) == 2 and len(cache.entries("thing")) == 2
    cache.clear()
    assert cache.entries() == []


def _entry(cdir):
    (d,) = cache.entries("thing")
    return d


def _count_builds(cdir, n=2):
    calls = []
    for _ in range(n):
        cache.load_or_build("thing", {"n": 1}, lambda: calls.append(1) or _value(), types=(Thing,))
    return len(calls)


def test_a_damaged_array_file_is_a_miss_and_is_rebuilt(cdir):
    cache.load_or_build("thing", {"n": 1}, _value, types=(Thing,))
    f = _entry(cdir) / "a0.npy"
    raw = bytearray(f.read_bytes())
    raw[-1] ^= 0x01  # one bit of the data, the header intact: only the checksum can tell
    f.write_bytes(bytes(raw))
    assert _count_builds(cdir, 2) == 1  # rebuilt once, then the new entry is read
    _same(cache.load(cache.key_for("thing", {"n": 1}), (Thing,))[0], _value())


def test_an_entry_of_another_key_or_a_foreign_class_or_pickled_data_is_never_used(cdir):
    cache.load_or_build("thing", {"n": 1}, _value, types=(Thing,))
    d = _entry(cdir)
    meta = json.loads((d / "meta.json").read_text(encoding="utf-8"))
    meta["key"]["inputs"] = {"n": 99}  # an entry filed under the key of other inputs
    (d / "meta.json").write_text(json.dumps(meta), encoding="utf-8")
    assert _count_builds(cdir, 1) == 1
    # a planted entry naming a class the caller did not allow: not instantiated, a miss
    key = cache.key_for("thing", {"n": 3})
    assert cache.save(key, {"o": Other(1)}, types=(Other,))
    assert cache.load(key, (Thing,)) is None
    # an array file holding pickled objects, with a matching checksum: np.load refuses it, a miss
    key = cache.key_for("thing", {"n": 4})
    assert cache.save(key, np.zeros(3), types=())
    (e,) = [p for p in cache.entries("thing") if json.loads((p / "meta.json").read_text())["key"] == key]
    np.save(e / "a0.npy", np.array([{"evil": 1}], dtype=object), allow_pickle=True)
    meta = json.loads((e / "meta.json").read_text())
    meta["files"][0][1] = cache._sha256(e / "a0.npy")
    (e / "meta.json").write_text(json.dumps(meta))
    assert cache.load(key) is None


@pytest.mark.skipif(not hasattr(os, "getuid"), reason="owners and modes are POSIX")
def test_a_folder_others_may_write_is_neither_read_nor_written(cdir):
    cache.load_or_build("thing", {"n": 1}, _value, types=(Thing,))
    os.chmod(cdir, 0o777)
    try:
        assert _count_builds(cdir, 2) == 2  # not read
        assert cache.save(cache.key_for("thing", {"n": 5}), 1.0) is False  # not written
    finally:
        os.chmod(cdir, 0o700)
    assert _count_builds(cdir, 1) == 0


@pytest.mark.parametrize("env", [{"AEROPHOTO_GRADING": "1"}, {"AEROPHOTO_CACHE": "0"}, {"AEROPHOTO_CACHE": "off"}])
def test_off_in_a_grading_kernel_and_when_switched_off(cdir, monkeypatch, env):
    cache.load_or_build("thing", {"n": 1}, _value, types=(Thing,))
    for k, v in env.items():
        monkeypatch.setenv(k, v)
    assert not cache.enabled()
    assert _count_builds(cdir, 2) == 2  # the entry on disk (a submission could carry one) is not read
    assert cache.save(cache.key_for("thing", {"n": 6}), 1.0) is False and len(cache.entries("thing")) == 1


def test_values_it_cannot_hold_stay_in_memory(cdir):
    calls = []
    got = cache.load_or_build("odd", {}, lambda: calls.append(1) or {"f": object()})
    assert isinstance(got["f"], object) and cache.entries("odd") == []
    with pytest.raises(TypeError, match="cannot cache"):
        cache.encode(np.array([object()]), [])


def test_the_key_holds_the_code_and_the_machine():
    k = cache.key_for("site", {"seed": 0})
    assert k["code"] == cache.code_fingerprint() and len(k["code"]) == 64
    assert {"numpy", "python", "machine", "cpu", "format"} <= set(k)
    assert cache.key_for("site", {"seed": 1}) != k


def test_the_site_read_from_the_cache_is_the_site_built(cdir):
    from aerophoto.site import Site, SiteObjects, SiteParams, build_site

    built = build_site(SiteParams())
    key = cache.key_for("site", dataclasses.asdict(SiteParams()))
    types = (Site, SiteObjects, SiteParams)
    assert cache.save(key, built, types)
    (read,) = cache.load(key, types)
    _same(read, built)
    assert read.height(5000.0, 2500.0) == built.height(5000.0, 2500.0)


def test_the_interpretation_site_is_built_once_and_read_back_bit_for_bit(cdir, monkeypatch):
    from aerophoto.site import cover

    calls = []
    real = cover.build_interpretation_site
    monkeypatch.setattr(cover, "build_interpretation_site", lambda seed=0: calls.append(seed) or real(seed))
    cover.interpretation_site.cache_clear()
    try:
        built = cover.interpretation_site(0)
        cover.interpretation_site.cache_clear()  # a new kernel: only the disk remembers
        read = cover.interpretation_site(0)
    finally:
        cover.interpretation_site.cache_clear()
    assert calls == [0] and read is not built
    _same(read, built)
    assert len(cache.entries("interpretation-site")) == 1
    assert read.texel_m == built.texel_m and repr(read) == repr(built)


def test_a_shipped_entry_is_read_only_in_the_browser_and_only_for_its_own_code(cdir, tmp_path, monkeypatch):
    """The browser book's precomputed entries (aerophoto.lite.shipped_wheel): read back bit for bit where the
    package's source is the one that wrote them, never on the desktop, in a grading kernel or when damaged."""
    import sys

    shipped = tmp_path / "shipped"
    monkeypatch.setattr(cache, "shipped_dir", lambda: shipped)
    d = cache.write_shipped(shipped, "thing", {"n": 1}, _value(), (Thing,))
    meta = json.loads((d / "meta.json").read_text(encoding="utf-8"))
    assert meta["key"] == cache.portable_key("thing", {"n": 1}) and set(meta["key"]) == {"format", "name", "inputs",
                                                                                            "code"}
    assert meta["made_on"]["python"] and meta["made_on"]["machine"]
    (read,) = cache.load_shipped("thing", {"n": 1}, (Thing,))
    _same(read, _value())
    assert cache.load_shipped("thing", {"n": 2}, (Thing,)) is None  # other inputs
    assert cache.shipped_hits()[-1] == "thing"

    built = []
    build = lambda: built.append(1) or "built"  # noqa: E731
    assert cache.load_or_build("thing", {"n": 1}, build, types=(Thing,)) == "built"  # the desktop builds
    cache.clear()
    monkeypatch.setattr(sys, "platform", "emscripten")  # the browser book reads the shipped entry
    _same(cache.load_or_build("thing", {"n": 1}, build, types=(Thing,)), _value())
    assert built == [1]
    monkeypatch.setenv("AEROPHOTO_GRADING", "1")
    assert cache.load_shipped("thing", {"n": 1}, (Thing,)) is None
    monkeypatch.delenv("AEROPHOTO_GRADING")

    monkeypatch.setattr(cache, "_FINGERPRINT", ["another version of the package"])
    assert cache.load_shipped("thing", {"n": 1}, (Thing,)) is None  # written by other code: never read
    monkeypatch.setattr(cache, "_FINGERPRINT", [])
    a0 = d / "a0.npy"
    a0.write_bytes(a0.read_bytes()[:-1] + b"\x01")
    assert cache.load_shipped("thing", {"n": 1}, (Thing,)) is None  # a damaged array


# =========================================================================== one cache, two halves
def test_the_reports_signed_half_shares_the_folder_key_switch_and_clear(cdir, monkeypatch):
    """aerophoto.diskcache (the report's signed entries) keeps no rules of its own: the folder is cache_dir(), the
    key is cache.key_for's (so another code fingerprint is another entry), the switch is cache.switched_off() and
    cache.clear() removes its entries too (its secret key stays)."""
    from aerophoto import diskcache

    with diskcache.enabled() as c:
        assert c is not None and c.folder == cdir
        c.json("t", {"a": 1}, lambda: {"x": 1})
        text = diskcache.canonical_key("t", {"a": 1})
        assert json.loads(text) == cache.key_for("t", {"a": 1})
        with pytest.raises(ValueError, match="key = "):
            diskcache.canonical_key("t", {"a": float("nan")})
        with monkeypatch.context() as m:
            m.setattr(cache, "_FINGERPRINT", ["another version of the package"])
            assert c.get_bytes("t", {"a": 1}) is None  # the code changed: a miss, not the old entry
        assert c.get_bytes("t", {"a": 1}) is not None
        cache.load_or_build("thing", {"n": 1}, lambda: np.arange(3))
        assert len(cache.entries()) == 1 and len(list(cdir.rglob("*.data"))) == 1
        cache.clear()
        assert cache.entries() == [] and list(cdir.rglob("*.data")) == [] and list(cdir.rglob("*.sig")) == []
        assert (cdir / "key").is_file()
        assert c.json("t", {"a": 1}, lambda: {"x": 2}) == {"x": 2}  # rebuilt after clear
    for off in ({"AEROPHOTO_CACHE": "off"}, {"AEROPHOTO_GRADING": "1"}):
        with monkeypatch.context() as m:
            for k, v in off.items():
                m.setenv(k, v)
            assert cache.switched_off()
            with diskcache.enabled() as c:
                assert c is None
