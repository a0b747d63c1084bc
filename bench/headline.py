"""The README's figures from the outputs bench/headline.sh collects: one line per row of its
table "Benchmarks and accuracy", each from the tables the programs printed.
    python3 bench/headline.py OUTPUT_DIR COMMIT MACHINE"""
import os
import re
import statistics
import sys

OUT, COMMIT, MACHINE = sys.argv[1:4]
# Open meshes: parity's inside is a surface's there, so a sprite's answers are not held to the exact
# classifier's (their figures are the generalized winding number's, vds_gwn_bench).
OPEN = ("stanford-bunny.obj", "suzanne.obj", "teapot.obj")


def text(name):
    path = os.path.join(OUT, name)
    return open(path).read() if os.path.exists(path) else ""


def tables(output):
    """Every markdown table of an output: (heading above it, header cells, rows of cells)."""
    heading = ""
    for block in re.split(r"\n\s*\n", output):
        lines = block.splitlines()
        if lines and lines[0].startswith("#"):
            heading = lines[0]
        rows = [l for l in lines if l.startswith("|")]
        if len(rows) > 2:
            cells = [[c.strip() for c in l.strip("|").split("|")] for l in rows]
            yield heading, cells[0], cells[2:]


def number(cell):
    m = re.match(r"^([0-9.]+(?:e[+-]?[0-9]+)?)\s*[x×%]?", cell)
    return float(m.group(1)) if m else None


def column(header, rows, name, keep=lambda row: True):
    i = header.index(name)
    return [v for v in (number(r[i]) for r in rows if keep(r)) if v is not None]


def number(value, digits):
    # `digits` significant digits, but never an exponent: 1070, not 1.07e+03
    text = "%.*g" % (digits, value)
    return "%.0f" % value if "e+" in text else text


def span(values, scale=1.0, unit="", digits=3):
    if not values:
        return "-"
    lo, hi = number(min(values) * scale, digits), number(max(values) * scale, digits)
    return lo + unit if lo == hi else "%s–%s%s" % (lo, hi, unit)


def say(row, figure):
    print("%s: %s" % (row, figure))


def vds_bench():
    output = text("bench.txt")
    renderer = re.search(r"GL[^\n]*(llvmpipe|NVIDIA|AMD|Intel|Mesa)[^\n]*", output)
    if renderer:
        print(renderer.group(0).strip())
    for _, header, rows in tables(output):
        if "CPU 1 thr" in header:
            two_name = next(h for h in header if re.match(r"CPU \d+ thr", h) and h != "CPU 1 thr")
            one, two, exact = (column(header, rows, n) for n in ("CPU 1 thr", two_name, "exact"))
            gpu = column(header, rows, "GPU host -> host") + column(header, rows, "GPU resident random") \
                + column(header, rows, "GPU resident coherent")
            same = all(r[header.index("GPU == CPU")] == "yes" for r in rows)
            say("classification, 10M random points, sprites at 2048, CPU",
                "%s M points/s on %s threads (%s on one); %s the exact classifier"
                % (span(two, 1e3), two_name.split()[1], span(one, 1e3),
                   span([t / e for t, e in zip(two, exact) if e > 0], unit="×")))
            say("classification on GL compute, host arrays or resident GL buffers",
                "%s M points/s, answers identical to the CPU's: %s" % (span(gpu, 1e3), "yes" if same else "NO"))
            say("accuracy, sprites at 2048, the same random points against the exact classifier, closed meshes",
                "%s of the points answered otherwise" % span(column(header, rows, "VDS vs exact",
                                                                    lambda r: r[0] not in OPEN), unit=" %", digits=2))
        if "cpu / lists" in header:
            bundled = lambda r: r[0].endswith(".obj")
            same = all(r[header.index("lists == peel")] == "yes" for r in rows)
            ratios = column(header, rows, "cpu / lists", bundled)
            say("bake at 1024, fragment lists vs the exact CPU baker and depth peeling",
                "lists %s the CPU baker's speed on the six public meshes (geometric mean %.2f×; %s in CPU time), "
                "%s faster than peeling; layers bit-identical to peeling's: %s"
                % (span(ratios, unit="×"), statistics.geometric_mean(ratios) if ratios else 0,
                   span(column(header, rows, "(CPU time)", bundled), unit="×"),
                   span(column(header, rows, "peel / lists", bundled), unit="×"), "yes" if same else "NO"))
        if "dense / .vds" in header:
            say(".vds file vs the paper's dense texture, 1024",
                "%s smaller on the six public meshes" % span(column(header, rows, "dense / .vds"), unit="×", digits=2))


def query_bench():
    certified_vs_sprite, certified_vs_exact, wrong, exact_path, sweep, sweep_wrong = [], [], 0, [], [], 0
    for heading, header, rows in tables(text("query.txt")):
        if "method" in header:
            rate = {(r[0], r[1]): number(r[header.index("M points/s")]) for r in rows}
            threads = max(r[1] for r in rows)
            certified = next(r for r in rows if r[0] == "certified")
            certified_vs_sprite.append(rate[("certified", threads)] / rate[("sprite, packed columns", threads)])
            certified_vs_exact.append(number(certified[header.index("vs exact")]))
            wrong += int(certified[header.index("wrong")])
            exact_path.append(number(certified[-1]))
        if "sweep vs exact per point" in header:
            sweep += column(header, rows, "sweep vs exact per point")
            sweep_wrong += sum(int(r[-1].split(",")[0]) for r in rows)
    if certified_vs_sprite:
        say("certified answers (exact) vs the sprite and the exact classifier, 1024, 2M uniform points, 2 threads",
            "%s the sprite's rate (packed columns), %s the exact classifier's, %d wrong; %s of the points take the "
            "exact path" % (span(certified_vs_sprite, unit="×", digits=2), span(certified_vs_exact, unit="×", digits=2),
                            wrong, span(exact_path, unit=" %", digits=2)))
    return sweep, sweep_wrong


def seconds(name):
    best = {}
    for line in text(name).splitlines():
        mesh, s = line.split()
        best[mesh] = min(best.get(mesh, 1e30), float(s))
    return best


def voxelize(sweep, sweep_wrong):
    spot = seconds("voxelize-spot.seconds")
    if spot:
        say("exact occupancy grid, spot at 256³ (`vds voxelize`)",
            "%.2f s for the whole command (best of 3); the exact sweep %s faster than classifying the cell centres one "
            "by one (spot, fandisk, rocker-arm at 256), %d cells unlike them" % (spot["spot"], span(sweep, unit="×", digits=2),
                                                                             sweep_wrong))


def peers():
    for heading, header, rows in tables(text("peers.txt")):
        if "× Embree" not in header:
            continue
        ratio = lambda method, threads="2": column(header, rows, "× Embree",
                                                   lambda r: r[2] == method and r[3] == threads)
        wrongs = lambda method: [int(r[header.index("wrong")].split()[0]) for r in rows if r[2].startswith(method)]
        wrong = lambda method: sum(wrongs(method))
        if "random points" in heading:
            sprite_one = column(header, rows, "M points/s", lambda r: r[2].startswith("vds sprite @") and r[3] == "1")
            sprite = [r for r in rows if r[2].startswith("vds sprite @")][0][2]
            say("random points against Embree ray parity, 1M points, 2 threads",
                "sprite %s Embree (%s M points/s on one thread); exact answers by the certified classifier %s, by the "
                "plain exact classifier %s, %d wrong" % (
                    span(ratio(sprite), unit="×", digits=2), span(sprite_one, digits=2),
                    span(ratio(sprite.replace("sprite", "certified")), unit="×", digits=2),
                    span(ratio("vds exact"), unit="×", digits=2),
                    wrong("vds exact") + wrong("vds certified")))
        if "grid" in heading:
            query = lambda method: column(header, rows, "query s", lambda r: r[2].startswith(method))
            sweep = "vds exact sweep"
            say("exact %s occupancy grid (`vds::occupancy`) against Embree on the cell centres" % heading.split()[2],
                "%s Embree (%s s against %s s), %d wrong cells (Embree %s a mesh)" % (
                    span([e / v for v, e in zip(query(sweep), query("Embree parity"))], unit="×", digits=3),
                    span(query(sweep), digits=2), span(query("Embree parity"), digits=2), wrong(sweep),
                    span(wrongs("Embree parity"))))


def distances():
    ratios = {"CGAL": [], "Embree": []}
    brute, signs = [], 0
    for name in ("distance-generated.txt", "distance-meshes.txt"):
        for section in re.split(r"\n(?=\S)", text(name)):  # one mesh's lines
            uniform = section.split("within")[0]
            for peer in ratios:
                m = re.search(r"\n\s+%s.*?([0-9.]+)x vds unsigned's time" % peer, uniform)
                if m:
                    ratios[peer].append(float(m.group(1)))
            brute += [float(x) for x in re.findall(r"vds - brute max ([0-9.e+-]+)", section)]
            signs += sum(int(x) for x in re.findall(r"(\d+) of \d+ points differ", section))
    grids = {}
    for kind in ("full, exact", "full, propagated", "band"):
        grids[kind] = [float(x) for x in re.findall(r"sdf [^,]*, %s, \d+ threads: ([0-9.]+) s" % kind, text("sdf-grids.txt"))]
    if ratios["CGAL"]:
        say("exact signed distance, 10^5 random points, 1 thread, against CGAL's AABB tree and Embree's point query",
            "%s CGAL, %s Embree on the generated and the six public meshes; %s from brute force (of the diagonal), "
            "%d signs unlike the exact classifier; SDF 256³ over 100k triangles on 2 threads: band ±3 cells %s s, "
            "full grid propagated %s s, full grid every cell exact %s s" % (
                span(ratios["CGAL"], unit="×", digits=2), span(ratios["Embree"], unit="×", digits=3),
                "at most %.1e" % max(brute) if brute else "-", signs, span(grids["band"], digits=2),
                span(grids["full, propagated"], digits=2), span(grids["full, exact"], digits=2)))


def gwn():
    exact, sprite, first, again, wrong, near = [], [], [], [], {}, []
    for _, header, rows in tables(text("gwn.txt")):
        if "again" not in header:
            continue
        by = {}
        for r in rows:
            by.setdefault(r[0], {})[r[2]] = r
        for mesh, methods in by.items():
            e = methods.get("exact GWN")
            s = next((r for m, r in methods.items() if m.startswith("sprite GWN")), None)
            if not e or not s:
                continue
            col = lambda r, name: number(r[header.index(name)])
            wrong.setdefault("exact", []).append(int(e[header.index("wrong")]))
            wrong.setdefault("sprite", []).append(int(s[header.index("wrong")]))
            exact.append(col(e, "all"))
            sprite.append(col(s, "all"))
            first.append(col(s, "all") / col(e, "all"))
            again.append(col(s, "again") / col(e, "again"))
            if col(e, "< 0.001"):
                near.append(col(e, ">= 0.1") / col(e, "< 0.001"))
    grids = seconds("voxelize-gwn.seconds")
    if exact:
        say("open meshes (bunny, teapot, suzanne and four generated hard cases), generalized winding number, "
            "200,000 uniform points, 1 thread",
            "exact GWN %d wrong, %s M points/s on the first call; points within 0.001 of w = 1/2 at most %.0f× the "
            "bulk's cost; sprites at 1024 %s M points/s, %s the exact path's rate on the first call and %s again, "
            "%s wrong labels (within a texel of the surface); exact `vds voxelize --rule generalized-winding` at 256³ "
            "on 2 threads %s s (%s)" % (
                sum(wrong["exact"]), span(exact, digits=2), max(near) if near else 0, span(sprite, digits=2),
                span(first, unit="×", digits=2), span(again, unit="×", digits=2), span(wrong["sprite"]),
                span(list(grids.values()), digits=2), ", ".join("%s %.2f" % kv for kv in grids.items())))


def axis():
    for _, header, rows in tables(text("axis.txt")):
        if "both in one call ms" in header:
            for r in rows:
                say("validation and the auto axis's choice of a %s-triangle mesh, one call, called again" % r[1],
                    "%s ms (validation %s, the count alone %s), best of 5" % (
                        r[header.index("both in one call ms")], r[header.index("validation ms")],
                        r[header.index("axis count ms")]))


def exact():
    rows = re.findall(r"^(\S+(?: \d+)?)\s+\d+\s.*?([0-9.]+)x\s+(\d+)/(\d+)$", text("exact.txt"), re.M)
    if rows:
        say("the exact classifier against the brute-force loop over every triangle, 1M random points",
            "%s faster (%s), the same answer on %d of %d points compared" % (
                span([float(r[1]) for r in rows], unit="×", digits=6),
                ", ".join("%s %s×" % (r[0], r[1]) for r in rows),
                sum(int(r[2]) for r in rows), sum(int(r[3]) for r in rows)))


def scans():
    grids = [t for t in tables(text("scans.txt")) if "band / full" in t[1]]
    if not grids:
        return
    _, header, rows = grids[0]
    occupancy = [number(r[header.index(next(h for h in header if h.startswith("GWN occupancy")))].split("=")[-1].strip())
                 for r in rows]
    band = column(header, rows, next(h for h in header if "SDF band" in h))
    ratio = column(header, rows, "band / full")
    boundary = column(header, rows, "boundary edges")
    sprite = []
    for _, h, rs in tables(text("scans-gwn.txt")):
        if "method" not in h:
            continue
        rate = {(r[0], r[h.index("method")].split(" @")[0]): number(r[h.index("all")]) for r in rs}
        sprite += [rate[(m, "sprite GWN")] / rate[(m, "exact GWN")] for (m, k) in rate
                   if k == "exact GWN" and (m, "sprite GWN") in rate and rate[(m, "exact GWN")]]
    say("real open scans: %d public scans with %d–%d boundary edges, 256³, 2 threads" % (
        len(rows), min(boundary), max(boundary)),
        "generalized-winding occupancy %s s; the ±3-cell SDF band %s s, %s of the full propagated grid; "
        "the sprite's GWN %s the exact path's rate on 200,000 uniform points" % (
            span(occupancy, digits=2), span(band, digits=2), span(ratio, digits=2), span(sprite, unit="×", digits=2)))


print("vds headline figures, commit %s" % COMMIT)
print("machine: %s" % MACHINE)
vds_bench()
voxelize(*query_bench())
peers()
distances()
gwn()
axis()
exact()
scans()
