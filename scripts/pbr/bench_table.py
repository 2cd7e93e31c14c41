"""Prints scripts/bench_pbr.sh's tables from its results.tsv (one line per sequence, setting
and camera, written by tests/bench/pbr_errors, prefixed by sequence, setting, CPU ms/frame and
the boundary contrast per camera).
  /usr/bin/python3 scripts/pbr/bench_table.py out/pbr/results.tsv
"""
import collections
import sys

COLS = ["cam", "frames", "rot", "rot_max", "ax", "ay", "az", "bx", "by", "bz", "sx", "sy", "sz",
        "worst", "lost"]

# pbr_errors --rotation: the rotation error vector log(R·R_gtᵀ) in the camera's axes (deg).
ROT_COLS = ["cam", "rbx", "rby", "rbz", "rsx", "rsy", "rsz", "step"]

rows = []
rotation_rows = []
with open(sys.argv[1]) as f:
    for line in f:
        p = line.rstrip("\n").split("\t")
        if p[4].endswith(":rotation"):
            r = dict(zip(ROT_COLS, p[4:]))
            for k in ROT_COLS[1:]:
                r[k] = float(r[k])
            r.update(seq=p[0], variant=p[1], cam=r["cam"].split(":")[0])
            rotation_rows.append(r)
            continue
        r = dict(zip(COLS, p[4:]))
        for k in COLS[1:]:
            r[k] = float(r[k])
        r.update(seq=p[0], variant=p[1], cpu=float(p[2]),
                 contrast=dict(kv.split("=") for kv in p[3].split()))
        rows.append(r)

HEAD = (f"{'sequence':<34} {'cam':<5} {'rot°':>6} {'max°':>6} {'|x|':>6} {'|y|':>6} {'|z|':>6} "
        f"{'bias x±sd':>14} {'bias y±sd':>14} {'bias z±sd':>14} {'worst':>6} {'lost':>4} "
        f"{'ms/f':>6} {'contr':>5}")


def fmt(name, cam, r, contrast=""):
    return (f"{name:<34} {cam:<5} {r['rot']:6.3f} {r['rot_max']:6.3f} {r['ax']:6.3f} {r['ay']:6.3f} "
            f"{r['az']:6.3f} {r['bx']:+7.3f}±{r['sx']:5.3f} {r['by']:+7.3f}±{r['sy']:5.3f} "
            f"{r['bz']:+7.3f}±{r['sz']:5.3f} {r['worst']:6.3f} {int(r['lost']):4d} "
            f"{r['cpu']:6.0f} {contrast:>5}")


def mean_row(rs):
    out = {k: sum(r[k] for r in rs) / len(rs) for k in COLS[2:] + ["cpu"] if k not in ("rot_max", "worst", "lost")}
    out["rot_max"] = max(r["rot_max"] for r in rs)
    out["worst"] = max(r["worst"] for r in rs)
    out["lost"] = sum(r["lost"] for r in rs)
    return out


for variant in ["annotate", "track", "cam0"]:
    vr = [r for r in rows if r["variant"] == variant and "#" not in r["cam"]]
    if not vr:
        continue
    print(f"\n### {variant}  (errors in each camera's frame at the bbox centre, mm / deg; "
          f"bias = mean signed error ± its standard deviation; ms/f = CPU per frame)")
    print(HEAD)
    for r in vr:
        print(fmt(r["seq"], r["cam"], r, r["contrast"].get(r["cam"], "")))
    by_cam = collections.defaultdict(list)
    for r in vr:
        by_cam[r["cam"]].append(r)
    for cam, rs in sorted(by_cam.items()):
        print(fmt("mean over sequences", cam, mean_row(rs)))
    print(fmt("mean over sequences and cameras", "all", mean_row(vr)))

blocks = [r for r in rows if r["variant"] == "annotate" and "#" in r["cam"]]
if blocks:
    print("\n### annotate: bias per 10-frame block (mm, camera axes)")
    print(f"{'sequence':<34} {'block':<7} {'bias x':>7} {'bias y':>7} {'bias z':>7} {'rot°':>6}")
    for r in blocks:
        print(f"{r['seq']:<34} {r['cam']:<7} {r['bx']:+7.3f} {r['by']:+7.3f} {r['bz']:+7.3f} {r['rot']:6.3f}")

if rotation_rows:
    print("\n### rotation error about each camera axis (deg): bias = mean of log(R·R_gtᵀ) ± its "
          "standard deviation; step = mean change from one frame to the next (≈ √2 × the spread "
          "when the error is independent from frame to frame, ≈ 0 when it drifts)")
    print(f"{'sequence':<34} {'setting':<9} {'cam':<5} {'about x':>14} {'about y':>14} "
          f"{'about z':>14} {'step':>6}")
    for r in rotation_rows:
        print(f"{r['seq']:<34} {r['variant']:<9} {r['cam']:<5} {r['rbx']:+7.3f}±{r['rsx']:5.3f} "
              f"{r['rby']:+7.3f}±{r['rsy']:5.3f} {r['rbz']:+7.3f}±{r['rsz']:5.3f} {r['step']:6.3f}")
