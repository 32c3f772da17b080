#!/usr/bin/env python3
"""The tables of README.md, from raw/t*/ (this session), ../issue40-final/raw/t*/ (the session
before) and ../inspect-h100/ratios-table-*.csv (the one before that). The three sessions timed
the same Rust and GLSL modules (spirv/ of f04d551) on three machines; this session also timed
the committed Rust set (HEAD). Run from this folder: python3 table.py."""
import csv, glob, json, math, statistics

Z = 1.959964


def cells(paths, first, second, null=False):
    """{(scene, spp): (ratio, low, high)} as time(second)/time(first), or the null as written."""
    out = {}
    for path in paths:
        for r in csv.DictReader(open(path)):
            if (r["null_control"] == "true") != null or not r["a"].endswith(first) or not r["b"].endswith(second):
                continue
            ratio, lo, hi = float(r["ratio"]), float(r["ci_low"]), float(r["ci_high"])
            out[(r["scene"], int(r["spp"]))] = (ratio, lo, hi) if null else (1 / ratio, 1 / hi, 1 / lo)
    return out


def cells_exact(paths, first, second):
    """As `cells`, for the sets named exactly `first` and `second` (the bundle's built-in ones)."""
    out = {}
    for path in paths:
        for r in csv.DictReader(open(path)):
            if r["null_control"] == "false" and r["a"] == first and r["b"] == second:
                ratio, lo, hi = float(r["ratio"]), float(r["ci_low"]), float(r["ci_high"])
                out[(r["scene"], int(r["spp"]))] = (1 / ratio, 1 / hi, 1 / lo)
    return out


def log_se(cell):
    """The standard error of log(ratio) that a 95% interval implies (bench's t intervals are
    read as normal ones here: the half-width over 1.96, a slight overestimate of the SE)."""
    _, lo, hi = cell
    return (math.log(hi) - math.log(lo)) / (2 * Z)


def inside(estimate, cell):
    return cell[1] <= estimate <= cell[2]


def coverage(passes):
    """How often one session's estimate lies inside another's 95% interval, over every
    ordered pair of sessions and every cell."""
    pairs = [(i, j) for i in range(len(passes)) for j in range(len(passes)) if i != j]
    hits = sum(inside(passes[j][k][0], passes[i][k]) for i, j in pairs for k in passes[i])
    return hits, len(pairs) * len(passes[0])


s3 = cells(glob.glob("raw/t*/*/ratios.csv"), "glsl", "old/rust")
s2 = cells(glob.glob("../issue40-final/raw/t*/*/ratios.csv"), "old/glsl", "old/rust")
s1 = cells(glob.glob("../inspect-h100/ratios-table-*.csv"), "glsl", "v192/rust")
head = {k: v for k, v in cells_exact(glob.glob("raw/t*/*/ratios.csv"), "glsl", "rust").items()}
nulls = cells(glob.glob("raw/t*/*/ratios.csv"), "glsl", "(copy 1)", null=True)

print("## The same modules in three sessions: Rust/GLSL (95% CI)\n")
print("| scene | spp | session 1 | session 2 | session 3 (this) | null (3) |")
print("|---|---|---|---|---|---|")
fmt = lambda c: f"{c[0]:.3f} ({c[1]:.3f} to {c[2]:.3f})"
for key in sorted(s3):
    print(f"| {key[0]} | {key[1]} | {fmt(s1[key])} | {fmt(s2[key])} | {fmt(s3[key])} | {fmt(nulls[key])} |")

passes = [s1, s2, s3]
hits, total = coverage(passes)
print(f"\nestimates inside another session's 95% interval: {hits} of {total}")
for name, (a, b) in {"1,2": (0, 1), "1,3": (0, 2), "2,3": (1, 2)}.items():
    h, t = coverage([passes[a], passes[b]])
    print(f"  sessions {name}: {h} of {t}")
d23 = [abs(math.log(s2[k][0] / s3[k][0])) for k in s3]
d13 = [abs(math.log(s1[k][0] / s3[k][0])) for k in s3]
print(f"median |log difference|: sessions 2 and 3 {100 * statistics.median(d23):.2f}%, "
      f"sessions 1 and 3 {100 * statistics.median(d13):.2f}%")
print(f"median SE of a cell's log ratio within a session: {statistics.median(log_se(c) for c in s3.values()):.4f}")

print("\n## Committed Rust set (HEAD) against GLSL, this session\n")
print("| scene | spp | HEAD Rust/GLSL (95% CI) | f04d551 Rust/GLSL | HEAD/f04d551 |")
print("|---|---|---|---|---|")
for key in sorted(head):
    print(f"| {key[0]} | {key[1]} | {fmt(head[key])} | {fmt(s3[key])} | {head[key][0] / s3[key][0]:.3f} |")
for name, table in {"HEAD": head, "f04d551": s3}.items():
    above = sorted(k for k, v in table.items() if v[1] > 1.01)
    print(f"\n{name}: median {statistics.median(v[0] for v in table.values()):.3f}; "
          f"wholly above 1.01: {len(above)} {above}")
print(f"\nnulls containing 1: {sum(v[1] <= 1 <= v[2] for v in nulls.values())} of {len(nulls)}; widest "
      f"{max(v[2] - v[1] for v in nulls.values()):.3f}")

print("\n## Each round at places of its own (raw/d13, device-13.sh): Rust/GLSL per round\n")
print("| cell | pass | 0 spacers | 1 | 2 | 3 | estimate (95% CI) | session 1 | sessions 2, 3 |")
print("|---|---|---|---|---|---|---|---|---|")
for path in sorted(glob.glob("raw/d13/*/*/results.json")):
    r = json.load(open(path))
    g, u = (next(x for x in r["rows"] if (x["set"] == "glsl") == want) for want in (True, False))
    rounds = [b / a for a, b in zip(g["placements"]["median_ms"], u["placements"]["median_ms"])]
    (ratio,) = [x for x in r["ratios"] if not x.get("null_control")]
    iv = ratio["interval"]
    key = (g["scene"], g["spp"])
    est = f"{1 / iv['ratio']:.3f} ({1 / iv['high']:.3f} to {1 / iv['low']:.3f})"
    print(f"| {key[0]} {key[1]} | {path.split('/')[2]} | " + " | ".join(f"{x:.3f}" for x in rounds)
          + f" | {est} | {s1[key][0]:.3f} | {s2[key][0]:.3f}, {s3[key][0]:.3f} |")
