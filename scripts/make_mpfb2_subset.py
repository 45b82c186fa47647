# Makes the MPFB2 asset subset that crowdlab ships in framework/body/assets/mpfb2/ from a full MPFB2 /
# MakeHuman asset folder (CC0; run by a maintainer when the subset changes, not part of CI):
#   python3 scripts/make_mpfb2_subset.py /path/to/full/mpfb2 framework/body/assets/mpfb2
#
# What is kept, and why (framework/body/mpfb2_model.hpp says what the loader reads):
#   3dobjs/base.obj                    as is (the loader needs the `body` group and the joint-cube groups;
#                                      vertex indices must not change, so nothing is renumbered)
#   rigs/standard/rig.mixamo.json      as is (the one rig crowdlab uses)
#   rigs/standard/weights.mixamo.json  as is
#   targets/macrodetails/macro.json    as is
#   LICENSE.md, LICENSE.ASSETS.md      as is (MPFB's licence text and the CC0 deed of the assets)
#   the macro targets that sample_mpfb2_bodies() can reach (sample_mpfb2_bodies.hpp): gender 0 or 1, age in
#   [0.5, 0.75] (young, old), muscle and weight in [0.1, 0.9] (min, average, max), height anywhere in [0, 1]
#   (min, max), proportions in [0.5, 1] (ideal only), any ethnic mix. tests/body/test_mpfb2_assets.cpp
#   checks that this list equals what the sampler reaches.
# Each kept target keeps only the offsets of vertices the loader reads (the `body` group, the joint-cube
# groups and the rig's MEAN vertices): helper geometry (tights, skirt, hair, eyes, teeth...) is never
# read, and dropping it saves ~30 %. The offsets themselves are copied verbatim (same text), re-gzipped
# with a zero timestamp so that the files are reproducible.
import gzip
import json
import shutil
import sys
from pathlib import Path

GENDERS = ["female", "male"]
AGES = ["young", "old"]
LEVELS = ["min", "average", "max"]
RACES = ["african", "asian", "caucasian"]


def reachable_targets():
    names = []
    for g in GENDERS:
        for a in AGES:
            for r in RACES:
                names.append(f"{r}-{g}-{a}")
            for m in LEVELS:
                for w in LEVELS:
                    stem = f"{g}-{a}-{m}muscle-{w}weight"
                    names.append(f"universal-{stem}")
                    names += [f"height/{stem}-{h}height" for h in ("min", "max")]
                    names.append(f"proportions/{stem}-idealproportions")
    return sorted(names)


def obj_groups(path):
    groups, current = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith("g "):
                current = line.split()[1]
                groups.setdefault(current, set())
            elif line.startswith("f "):
                groups[current].update(int(t.split("/")[0]) - 1 for t in line.split()[1:])
    return groups


def read_vertices(src):
    groups = obj_groups(src / "3dobjs" / "base.obj")
    keep = set(groups["body"])
    rig = json.loads((src / "rigs" / "standard" / "rig.mixamo.json").read_text())
    for bone in rig["bones"].values():
        for end in ("head", "tail"):
            p = bone[end]
            if p["strategy"] == "CUBE":
                keep |= groups[p["cube_name"]]
            elif p["strategy"] == "MEAN":
                keep |= set(p["vertex_indices"])
    return keep


def strip_target(src_file, dst_file, keep):
    dst_file.parent.mkdir(parents=True, exist_ok=True)
    with gzip.open(src_file, "rt") as f:
        lines = [l for l in f if l.startswith("#") or not l.strip() or int(l.split()[0]) in keep]
    with open(dst_file, "wb") as raw:
        with gzip.GzipFile(filename="", mode="wb", compresslevel=9, fileobj=raw, mtime=0) as gz:
            gz.write("".join(lines).encode())


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_mpfb2_subset.py FULL_MPFB2_DIR OUT_DIR")
    src, dst = Path(sys.argv[1]), Path(sys.argv[2])
    for rel in ["3dobjs/base.obj", "rigs/standard/rig.mixamo.json", "rigs/standard/weights.mixamo.json",
                "targets/macrodetails/macro.json", "LICENSE.md", "LICENSE.ASSETS.md"]:
        (dst / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src / rel, dst / rel)
    keep = read_vertices(src)
    for name in reachable_targets():
        rel = Path("targets/macrodetails") / (name + ".target.gz")
        strip_target(src / rel, dst / rel, keep)


if __name__ == "__main__":
    main()
