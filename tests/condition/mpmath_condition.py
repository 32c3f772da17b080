"""The condition numbers of twinray's probe reports, recomputed with mpmath (tests/condition.rs).

Reads the JSON file named on the command line: rays, each with the object it hits (its shape in
object space and its object-to-world transform) and twinray's f64 answers, t and kappa. For each
ray it finds t again at 50 digits as the root of the shape's implicit function along the ray,
then moves each of the problem's inputs, as seen from the object (the ray's start relative to
the object's origin, its direction, and the transform's 3x3 part), by a relative 1e-30 in turn,
solves again, and sums |dt/dp * p| / t: kappa by perturbation, independent of twinray's formula.
The translation is not an input of its own: where the world's origin lies is not the problem's. Prints one line per ray and exits 1
where the two kappas, or the two t, disagree by more than 1e-9 relative.
"""
import json
import sys

from mpmath import mp, mpf, matrix, sqrt, findroot

mp.dps = 50


def implicit(shape, x):
    """The shape's implicit function at the object-space point x: 0 on its surface."""
    kind, p = shape["kind"], [mpf(v) for v in shape["params"]]
    if kind == "sphere":
        c, r = p[0:3], p[3]
        return sum((x[i] - c[i]) ** 2 for i in range(3)) - r * r
    if kind == "torus":
        major, minor = p
        return (sqrt(x[0] ** 2 + x[2] ** 2) - major) ** 2 + x[1] ** 2 - minor * minor
    if kind == "cylinder":
        return x[0] ** 2 + x[2] ** 2 - p[0] ** 2
    if kind == "box":
        return max(abs(x[i]) - p[i] for i in range(3))
    if kind == "triangle":
        v0, v1, v2 = p[0:3], p[3:6], p[6:9]
        e1 = [v1[i] - v0[i] for i in range(3)]
        e2 = [v2[i] - v0[i] for i in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        return sum(n[i] * (x[i] - v0[i]) for i in range(3))
    raise ValueError(kind)


def solve(ray, inputs, guess):
    """t where the ray of `inputs` (start relative to the object's origin, direction, 3x3 part by
    rows) meets the shape."""
    s, d, m = inputs[0:3], inputs[3:6], inputs[6:15]
    inverse = matrix([[m[3 * r + c] for c in range(3)] for r in range(3)]) ** -1

    def g(t):
        w = matrix([s[i] + t * d[i] for i in range(3)])
        x = inverse * w
        return implicit(ray["shape"], [x[0], x[1], x[2]])

    return findroot(g, guess, tol=mpf(10) ** -45)


def main():
    rays = json.load(open(sys.argv[1]))
    bad = 0
    for ray in rays:
        start = [mpf(o) - mpf(tr) for o, tr in zip(ray["origin"], ray["translation"])]
        inputs = start + [mpf(v) for v in ray["direction"] + ray["matrix"]]
        t = solve(ray, inputs, mpf(ray["t"]))
        total = mpf(0)
        for k, value in enumerate(inputs):
            if value == 0:
                continue
            h = value * mpf(10) ** -30
            moved = list(inputs)
            moved[k] = value + h
            total += abs((solve(ray, moved, t) - t) / h * value)
        kappa = total / t
        t_off = abs(t - mpf(ray["t"])) / t
        kappa_off = abs(kappa - mpf(ray["kappa"])) / kappa
        ok = t_off < 1e-9 and kappa_off < 1e-9
        bad += not ok
        print(f'{ray["name"]}: t {float(t):.12g} (off {float(t_off):.1e}), kappa {float(kappa):.12g} '
              f'against {ray["kappa"]:.12g} (off {float(kappa_off):.1e}){"" if ok else "  DISAGREE"}')
    sys.exit(1 if bad else 0)


main()
