#!/usr/bin/env python3
"""Copies the MakeHuman proxy assets crowdlab dresses its MPFB2 bodies in (CC0) into
framework/body/assets/makehuman, and writes wardrobe.txt (framework/body/mpfb2_outfit.hpp).

Usage: scripts/make_makehuman_subset.py SRC DEST
  SRC   a makehuman-assets checkout's base/ folder (clothes/, hair/, eyebrows/)
  DEST  framework/body/assets/makehuman

Each .mhclo is copied unchanged. Each OBJ keeps its comment header, `v` and `f` lines only, with the
texture and normal indices dropped from faces (crowdlab reads positions and faces; there are no textures),
and vertex coordinates as written. The .mhmat materials are not copied (crowdlab shades from colours).
"""
import pathlib
import re
import shutil
import sys

WARDROBE = [
    ("outfit_male", "clothes/male_casualsuit02"),
    ("outfit_male", "clothes/male_casualsuit04"),
    ("outfit_male", "clothes/male_casualsuit06"),
    ("outfit_female", "clothes/female_casualsuit01"),
    ("outfit_female", "clothes/female_sportsuit01"),
    ("outfit_female", "clothes/female_elegantsuit01"),
    ("hair_male", "hair/short02"),
    ("hair_male", "hair/short03"),
    ("hair_male", "hair/short04"),
    ("hair_female", "hair/short03"),
    ("hair_female", "hair/ponytail01"),
    ("hair_female", "hair/long01"),
    ("shoes", "clothes/shoes01"),
    ("shoes", "clothes/shoes02"),
    ("eyebrows", "eyebrows/eyebrow001"),
    ("eyebrows", "eyebrows/eyebrow006"),
]


def obj_file(mhclo: pathlib.Path) -> str:
    for line in mhclo.read_text().splitlines():
        if line.startswith("obj_file "):
            return line.split()[1]
    raise SystemExit(f"{mhclo}: no obj_file line")


def strip_obj(src: pathlib.Path, dest: pathlib.Path) -> None:
    out = []
    for line in src.read_text().splitlines():
        if line.startswith("#") or line.startswith("v "):
            out.append(line)
        elif line.startswith("f "):
            out.append("f " + " ".join(t.split("/")[0] for t in line.split()[1:]))
    dest.write_text("\n".join(out) + "\n")


def main() -> None:
    src, dest = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    dest.mkdir(parents=True, exist_ok=True)
    lines = ["# category  .mhclo (relative to this folder); written by scripts/make_makehuman_subset.py"]
    for category, folder in WARDROBE:
        name = pathlib.Path(folder).name
        mhclo = src / folder / f"{name}.mhclo"
        (dest / folder).mkdir(parents=True, exist_ok=True)
        shutil.copyfile(mhclo, dest / folder / mhclo.name)
        obj = obj_file(mhclo)
        strip_obj(src / folder / obj, dest / folder / obj)
        lines.append(f"{category} {folder}/{mhclo.name}")
    (dest / "wardrobe.txt").write_text("\n".join(lines) + "\n")
    shutil.copyfile(src.parent / "LICENSE.txt", dest / "LICENSE.txt")


if __name__ == "__main__":
    main()
