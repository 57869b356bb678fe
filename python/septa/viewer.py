"""``septa.view``: the browser viewer for a result, as a self-contained
folder (index.html, the bundled viewer.js with three.js, and data.js holding
the result), exactly as ``septa view OUTDIR`` writes it."""
from __future__ import annotations

import json
import os
import tempfile
import webbrowser
from pathlib import Path

from . import _septa
from .network import Network, load

__all__ = ["view", "write_viewer", "inline_html"]


def _payload(net: Network, title: str) -> str:
    payload = {"title": title, "network": net.data, "cut": None}
    return "window.__SEPTA_DATA = " + json.dumps(payload, separators=(",", ":")) + ";\n"


def inline_html(net: Network, title: str = "Septa", height: int = 480) -> str:
    """The viewer for ``net`` as one ``<iframe srcdoc=...>`` (the bundled
    viewer, three.js and the result inline; nothing is loaded from the
    network): what a notebook shows for a :class:`Network`."""
    import html

    files = dict(_septa.viewer_assets())
    page = files["index.html"].decode()
    script = lambda js: "<script>" + js.replace("</script", "<\\/script") + "</script>"
    page = page.replace('<script src="data.js"></script>', script(_payload(net, title)))
    page = page.replace('<script src="viewer.js"></script>', script(files["viewer.js"].decode()))
    return (f'<iframe srcdoc="{html.escape(page, quote=True)}" style="width:100%;height:{int(height)}px;border:0" '
            f'sandbox="allow-scripts"></iframe>')


def write_viewer(net: Network, folder, title: str = "Septa") -> Path:
    """Writes the viewer folder for ``net``; returns the path of index.html."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    files = dict(_septa.viewer_assets())
    files["data.js"] = _payload(net, title).encode()
    for name, data in files.items():
        tmp = folder / (name + ".tmp-septa")
        try:
            tmp.write_bytes(data)
            os.replace(tmp, folder / name)
        finally:  # a failed write leaves the old file and no temporary
            if tmp.exists():
                tmp.unlink()
    return (folder / "index.html").resolve()


def view(result, folder=None, *, open: bool = True, title: str | None = None) -> Path:
    """Writes a viewer for ``result`` (a :class:`Network` or a job output
    folder) and opens it in a browser when there is one; returns index.html.

    Without ``folder``, writes into ``<result folder>/viewer`` for loaded
    results, else into a new temporary folder.
    """
    if hasattr(result, "_viewer_network"):  # septa.CutCells: its cells as a network
        net = result._viewer_network()
    else:
        net = result if isinstance(result, Network) else load(result)
    if folder is None:
        src = getattr(net, "source", None)
        folder = Path(src).parent / "viewer" if src else Path(tempfile.mkdtemp(prefix="septa-view-"))
    index = write_viewer(net, folder, title or (Path(net.source).parent.name if getattr(net, "source", None) else "Septa"))
    opened = False
    if open and (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY") or os.name == "nt" or os.uname().sysname == "Darwin"):
        opened = webbrowser.open(index.as_uri())
    if not opened:
        print(f"viewer: {index}")
    return index
