"""004 Table 5.1 read as the continuous normal it samples: print a `size_distribution` scene value.

Sec. 5.1.3 generates its spheres with "a Gaussian size distribution (as shown in Table 5.1)"; the table
lists nine diameters 0.59-1.41 mm with number frequencies, the histogram of a normal with the mean
0.9989 mm and standard deviation 0.1385 mm it implies, cut at about three standard deviations. The scenes
sample the table's nine classes as printed (docs/models.md). This prints the other reading: 43 classes
0.02 mm apart over 0.58-1.42 mm, frequencies from the normal's density, its width set so that the
classes' standard deviation by number is the table's (benches/ch5_soft_proxy.sh, rows fric_psd).

    python3 benches/ch5_normal_psd.py
"""
import json
import math

TABLE_5_1 = ([0.59, 0.72, 0.81, 0.9, 1.0, 1.1, 1.19, 1.28, 1.41], [0.33, 3.84, 11.24, 21.0, 27.75, 20.85, 10.95, 3.74, 0.29])


def moments(d, f):
    """Mean and standard deviation by number [mm]."""
    n = sum(f)
    mean = sum(a * b for a, b in zip(d, f)) / n
    return mean, math.sqrt(sum(b * (a - mean) ** 2 for a, b in zip(d, f)) / n)


def classes(mean, width, d_min=0.58, d_max=1.42, step=0.02):
    d = [round(d_min + step * i, 10) for i in range(round((d_max - d_min) / step) + 1)]
    f = [math.exp(-0.5 * ((x - mean) / width) ** 2) for x in d]
    total = sum(f)
    return d, [100 * x / total for x in f]


def main():
    mean, sd = moments(*TABLE_5_1)
    lo, hi = 0.5 * sd, 2.0 * sd  # the width whose classes have the table's standard deviation (bisection)
    for _ in range(100):
        width = 0.5 * (lo + hi)
        if moments(*classes(mean, width))[1] < sd:
            lo = width
        else:
            hi = width
    d, f = classes(mean, width)
    got = moments(d, f)
    assert abs(got[0] - mean) < 1e-3 and abs(got[1] - sd) < 1e-9, got
    print(json.dumps({"diameters": [round(x * 1e-3, 9) for x in d], "frequencies": [round(x, 6) for x in f]}))


if __name__ == "__main__":
    main()
