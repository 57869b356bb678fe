"""``septa.view``: the browser viewer for a result, as a self-contained
folder (index.html, the bundled viewer.js with three.js, and data.js holding
the result). The page and its data are written by the library's one viewer
writer, the one ``septa view OUTDIR`` uses: a folder viewed from Python and
from the command line gives the same files."""
from __future__ import annotations

import html
import json
import os
import tempfile
import webbrowser
from pathlib import Path

from . import _septa
from .network import Network, load

__all__ = ["view", "write_viewer", "inline_html"]


def _network_json(net: Network) -> str:
    return json.dumps(net.data, separators=(",", ":"))


def inline_html(net: Network, title: str = "Septa", height: int = 480) -> str:
    """The viewer for ``net`` as one ``<iframe srcdoc=...>`` (the bundled
    viewer, three.js and the result inline; nothing is loaded from the
    network): what a notebook shows for a :class:`Network`."""
    page = _septa.viewer_page(_network_json(net), title)
    return (f'<iframe srcdoc="{html.escape(page, quote=True)}" style="width:100%;height:{int(height)}px;border:0" '
            f'sandbox="allow-scripts"></iframe>')


def write_viewer(net: Network, folder, title: str = "Septa") -> Path:
    """Writes the viewer folder for ``net``; returns the path of index.html."""
    return Path(_septa.viewer_write(str(folder), _network_json(net), title))


def _shown_by_library(p: Path) -> bool:
    """Whether the library reads this result itself: a folder with
    network.json, a cut's cells.obj or a stream, or a stream file; a folder
    with only network.npz (``--format npz``) is loaded here first."""
    if p.is_file():
        return p.suffix.lower() in (".ply", ".vtu")
    return not ((p / "network.npz").exists() and not (p / "network.json").exists())


def view(result, folder=None, *, open: bool = True, title: str | None = None) -> Path:
    """Writes a viewer for ``result`` (a :class:`Network`, a job output
    folder, or a stream's ``OUT.ply`` / ``OUT.vtu``) and opens it in a browser
    when there is one; returns index.html.

    Without ``folder``, writes into ``<result folder>/viewer`` for results on
    disk, else into a new temporary folder.
    """
    cut = hasattr(result, "_viewer_network")  # septa.CutCells: its cells as a network
    if not cut and not isinstance(result, Network) and _shown_by_library(Path(result)):
        p = Path(result)
        base = p if p.is_dir() else p.parent
        name = title or base.resolve().name or "Septa"
        index = Path(_septa.viewer_write_result(str(p), name, None if folder is None else str(folder)))
    else:
        net = result._viewer_network() if cut else result if isinstance(result, Network) else load(result)
        if folder is None:
            src = getattr(net, "source", None)
            folder = Path(src).parent / "viewer" if src else Path(tempfile.mkdtemp(prefix="septa-view-"))
        name = title or (Path(net.source).parent.name if getattr(net, "source", None) else "Septa")
        index = write_viewer(net, folder, name)
    opened = False
    if open and (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY") or os.name == "nt" or os.uname().sysname == "Darwin"):
        opened = webbrowser.open(index.as_uri())
    if not opened:
        print(f"viewer: {index}")
    return index
