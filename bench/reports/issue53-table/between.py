"""How far two runs of the table differ beyond what their intervals predict: for each pair of
runs, the rms of the cells' log differences, the rms their standard errors predict, the
between-run part left (the square root of the difference of squares), the mean signed
difference, and z, each difference over its standard error (rms 1 when the intervals are
right). Reads raw/ through table.py.
    python3 between.py"""
import contextlib
import importlib.util
import io
import math
import os
import statistics
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.argv = ["table.py", "l1", "l2"]
spec = importlib.util.spec_from_file_location("table", os.path.join(here, "table.py"))
table = importlib.util.module_from_spec(spec)
with contextlib.redirect_stdout(io.StringIO()):
    spec.loader.exec_module(table)

print("| runs | cells | rms difference | predicted | between runs | mean difference | rms z |")
print("|---|---|---|---|---|---|---|")
for a, b in [("u1", "u2"), ("p1+s1", "p2+s2"), ("l1", "l2"), ("n1", "n2"), ("y1", "y2"), ("y1", "y3"), ("y2", "y3")]:
    one, two = table.layered(a), table.layered(b)
    ds, variances, zs = [], [], []
    for key in one:
        if key not in two:
            continue
        (se1, _), (se2, _) = one[key]["se"], two[key]["se"]
        d = math.log(two[key]["ratio"][0] / one[key]["ratio"][0])
        ds.append(d)
        variances.append(se1 * se1 + se2 * se2)
        zs.append(d / math.hypot(se1, se2))
    observed = math.sqrt(sum(d * d for d in ds) / len(ds))
    predicted = math.sqrt(sum(variances) / len(variances))
    between = math.sqrt(max(observed * observed - predicted * predicted, 0.0))
    rms_z = math.sqrt(sum(z * z for z in zs) / len(zs))
    print(
        f"| {a} / {b} | {len(ds)} | {observed * 100:.3f}% | {predicted * 100:.3f}% | {between * 100:.3f}% "
        f"| {statistics.mean(ds) * 100:+.3f}% | {rms_z:.2f} |"
    )
