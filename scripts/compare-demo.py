#!/usr/bin/python3
"""Compares two `proxima demo` output directories: every image byte for byte and every
deterministic metric and table cell exactly; timings (names with ms, fps, time, seconds,
speed-up, ÷, _over_; the bench section's time ratios bench_*_ratio) and prose are skipped. Exit 0 when equal, 1 with the differences listed.

  scripts/compare-demo.py OLD_DIR NEW_DIR
"""
import json
import math
import pathlib
import re
import sys

TIMING = re.compile(r"(^|[_ ])(ms|fps|seconds|minutes)($|[_ ])|_ms|time|speed|÷|_over_|frame rate|stages|build_ms"
                    r"|^bench_.*_ratio$", re.IGNORECASE)


def same_number(a, b):
    if a is None or b is None:
        return a is None and b is None
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return a == b or (math.isnan(a) and math.isnan(b))


SKIPPED = {"metrics": 0, "compared": 0}


def compare_results(old, new, where, diffs):
    for name in sorted(set(old["metrics"]) | set(new["metrics"])):
        if TIMING.search(name):
            SKIPPED["metrics"] += 1
            continue
        SKIPPED["compared"] += 1
        a, b = old["metrics"].get(name, "missing"), new["metrics"].get(name, "missing")
        if not same_number(a, b):
            diffs.append(f"{where}: metric {name}: {a} != {b}")
    old_tables = {t["title"]: t for t in old["tables"]}
    new_tables = {t["title"]: t for t in new["tables"]}
    for title in sorted(set(old_tables) | set(new_tables)):
        if title not in old_tables or title not in new_tables:
            diffs.append(f"{where}: table '{title}' only in one run")
            continue
        if TIMING.search(title):
            continue
        a, b = old_tables[title], new_tables[title]
        if a["columns"] != b["columns"] or len(a["rows"]) != len(b["rows"]):
            diffs.append(f"{where}: table '{title}' has other columns or rows")
            continue
        rows_a, rows_b = a["rows"], b["rows"]
        if title.startswith("Error vs ms"):  # the bench's curves list their points in time order
            def key(row):
                return [str(c) for column, c in zip(a["columns"], row) if not TIMING.search(column)]
            rows_a, rows_b = sorted(rows_a, key=key), sorted(rows_b, key=key)
        for r, (ra, rb) in enumerate(zip(rows_a, rows_b)):
            for column, ca, cb in zip(a["columns"], ra, rb):
                if not TIMING.search(column) and not same_number(ca, cb):
                    diffs.append(f"{where}: table '{title}' row {r} {column}: {ca} != {cb}")
    if old["images"] != new["images"]:
        diffs.append(f"{where}: image roles differ")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    old_dir, new_dir = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    diffs, images, results = [], 0, 0
    old_files = {p.relative_to(old_dir) for p in old_dir.rglob("*") if p.is_file()}
    new_files = {p.relative_to(new_dir) for p in new_dir.rglob("*") if p.is_file()}
    for rel in sorted(old_files | new_files):
        if rel.suffix not in (".png", ".json"):
            continue
        if rel not in old_files or rel not in new_files:
            diffs.append(f"{rel}: only in {'old' if rel in old_files else 'new'}")
        elif rel.suffix == ".png":
            images += 1
            if (old_dir / rel).read_bytes() != (new_dir / rel).read_bytes():
                diffs.append(f"{rel}: images differ")
        elif rel.name != "results.json":
            if (old_dir / rel).read_bytes() != (new_dir / rel).read_bytes():
                diffs.append(f"{rel}: files differ")
        else:
            results += 1
            compare_results(json.loads((old_dir / rel).read_text()), json.loads((new_dir / rel).read_text()),
                            str(rel), diffs)
    for d in diffs:
        print(d)
    print(f"compared {images} images and {results} results.json ({SKIPPED['compared']} metrics, "
          f"{SKIPPED['metrics']} timings skipped): {len(diffs)} differences")
    sys.exit(1 if diffs else 0)


if __name__ == "__main__":
    main()
