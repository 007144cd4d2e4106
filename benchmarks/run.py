"""Run the benchmarks and print one JSON document.

    python benchmarks/run.py                 # every bench_*.py
    python benchmarks/run.py displacement    # only bench_displacement.py
    python benchmarks/run.py --quick         # fewer repetitions (a smoke run)

Each ``benchmarks/bench_<name>.py`` defines ``run(quick: bool = False) -> dict``.
The results are also written to ``benchmarks/results/latest.json`` (git-ignored).
Speed is measured here, never asserted in tests: the machine is shared and noisy.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def _load(path: Path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[path.stem] = mod
    spec.loader.exec_module(mod)
    return mod


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", help="benchmark names (bench_<name>.py); default: all")
    ap.add_argument("--quick", action="store_true", help="fewer repetitions")
    args = ap.parse_args(argv)
    # the benchmark scripts `from _timing import ...`: register it as a module (no sys.path edits)
    machine = _load(HERE / "_timing.py").machine

    files = sorted(HERE.glob("bench_*.py"))
    if args.names:
        files = [f for f in files if f.stem.removeprefix("bench_") in args.names]
    out = {"machine": machine(), "started": time.strftime("%Y-%m-%dT%H:%M:%S"), "results": {}}
    for f in files:
        mod = _load(f)
        t0 = time.perf_counter()
        out["results"][f.stem.removeprefix("bench_")] = mod.run(quick=args.quick)
        print(f"# {f.name}: {time.perf_counter() - t0:.1f} s", file=sys.stderr)
    text = json.dumps(out, indent=2, ensure_ascii=False)
    print(text)
    (HERE / "results").mkdir(exist_ok=True)
    (HERE / "results" / "latest.json").write_text(text + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
