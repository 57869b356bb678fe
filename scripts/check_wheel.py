"""Checks the wheel `maturin build --release` made (run by scripts/test.sh).

What the README promises workers and users who copy it elsewhere
(docs/distributed.md): one wheel for every CPython >= 3.9 (tag cp39-abi3),
installable on other Linux systems (a manylinux platform tag, which
maturin only gives after checking the library's glibc symbol versions),
small (the library stripped of debug info: it was 40 MB with it), holding
the Python package and its compiled core.

Usage: python scripts/check_wheel.py dist/septa-*.whl [--max-mb 6]
Prints the wheel's name, tag and sizes; exits 1 naming what is wrong.
"""
import argparse
import re
import struct
import sys
import zipfile
from pathlib import Path


def elf_sections(data: bytes) -> list:
    """Section names of a 64-bit little-endian ELF file."""
    if data[:4] != b"\x7fELF" or data[4] != 2 or data[5] != 1:
        raise ValueError("not a 64-bit little-endian ELF file")
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
    headers = [struct.unpack_from("<IIQQQQ", data, shoff + i * shentsize) for i in range(shnum)]
    str_off, str_size = headers[shstrndx][4], headers[shstrndx][5]
    table = data[str_off:str_off + str_size]
    return [table[h[0]:table.index(b"\0", h[0])].decode() for h in headers]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("wheel", type=Path)
    ap.add_argument("--max-mb", type=float, default=6.0, help="largest wheel accepted (MB)")
    a = ap.parse_args()
    problems = []
    name = a.wheel.name
    m = re.fullmatch(r"septa-([^-]+)-cp39-abi3-(manylinux_\d+_\d+_x86_64|manylinux2014_x86_64)(\..*)?\.whl", name)
    if not m:
        problems.append(f"{name}: expected septa-<version>-cp39-abi3-manylinux_*_x86_64.whl")
    size_mb = a.wheel.stat().st_size / 1e6
    if size_mb > a.max_mb:
        problems.append(f"{name}: {size_mb:.1f} MB, more than {a.max_mb} MB (is the library stripped?)")
    with zipfile.ZipFile(a.wheel) as z:
        names = z.namelist()
        libs = [n for n in names if re.fullmatch(r"septa/_septa\.(abi3\.)?so", n)]
        if len(libs) != 1:
            problems.append(f"{name}: expected one septa/_septa.abi3.so, found {libs}")
        for must in ("septa/__init__.py", "septa/py.typed"):
            if must not in names:
                problems.append(f"{name}: {must} is missing")
        tags = [line.split(":", 1)[1].strip() for line in
                z.read(next(n for n in names if n.endswith(".dist-info/WHEEL"))).decode().splitlines()
                if line.startswith("Tag:")]
        lib_mb = 0.0
        if libs:
            data = z.read(libs[0])
            lib_mb = len(data) / 1e6
            debug = [s for s in elf_sections(data) if s.startswith(".debug")]
            if debug:
                problems.append(f"{libs[0]}: not stripped (sections {', '.join(debug)})")
    print(f"{name}: {size_mb:.1f} MB, tag {', '.join(tags)}, library {lib_mb:.1f} MB")
    for p in problems:
        print(f"check_wheel: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
