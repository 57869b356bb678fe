"""Shared by the scripts of scripts/reproduce/: running septa and printing the seed papers'
numbers beside Septa's."""
import json
import os
import subprocess
import sys


def septa_path(arg):
    """The septa program given on the command line (a path, or a name on PATH)."""
    p = os.path.abspath(arg) if os.sep in arg else arg
    if os.sep in p and not os.access(p, os.X_OK):
        sys.exit(f"not an executable program: {arg} (build it with `cargo build --release`: target/release/septa)")
    return p


def run_json(cmd):
    """Runs septa with --json; returns (exit code, list of JSON objects printed, stderr)."""
    r = subprocess.run(cmd, capture_output=True, text=True)
    objs = []
    for line in r.stdout.splitlines():
        line = line.strip()
        if line.startswith("{"):
            try:
                objs.append(json.loads(line))
            except ValueError:
                pass
    if not objs and r.stdout.strip().startswith("{"):
        try:
            objs.append(json.loads(r.stdout))
        except ValueError:
            pass
    return r.returncode, objs, r.stderr


def table(title, header, rows):
    """Prints a Markdown table."""
    print(f"\n{title}\n")
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---" for _ in header) + "|")
    for r in rows:
        print("| " + " | ".join(str(x) for x in r) + " |")


def pct(n, total):
    return f"{100.0 * n / total:.2f}%" if total else "-"
