"""Type stubs of the compiled core (crates/septa-py)."""
import numpy as np
import numpy.typing as npt

__version__: str

class InputError(ValueError):
    """Bad input: the message names what is wrong and where."""

def check_values(values: npt.NDArray[np.float64], name: str = "values") -> None: ...
def check_tets(tets: npt.NDArray[np.int64], n_vertices: int) -> None: ...
def viewer_assets() -> dict[str, bytes]: ...
def read_input(path: str) -> bytes: ...
def check_input_file(path: str) -> int: ...
def check_output_file(path: str) -> None: ...
def network(
    mode: str,
    vertices: npt.NDArray[np.float64],
    tets: npt.NDArray[np.int64],
    values: npt.NDArray[np.float64],
    box: tuple[tuple[int, int, int], list[list[float]], int] | None = None,
    lookup: bool = True,
    raytrace: bool = True,
    threads: int | None = None,
    progress: object | None = None,
    certify: bool = True,
) -> dict: ...

def regions(scene: str, normals: bool = False, clean: float | None = None,
            progress: object | None = None, certify: bool = True) -> dict:
    """Region surfaces of a scene (path, ``builtin:NAME`` or JSON text) as numpy arrays (``septa.Network``'s names)."""

def labels(volume: np.ndarray, sigma: float = 0.0, progress: object | None = None,
           affine: list[list[float]] | None = None, certify: bool = True) -> dict:
    """Surfaces between the labels of an int64 ``(nx, ny, nz)`` volume as numpy arrays (as ``regions``)."""

def write_result(path: str, format: str, mode: str, functions: int, points: np.ndarray, offsets: np.ndarray,
                 indices: np.ndarray, patch: np.ndarray, labels: np.ndarray, cells: np.ndarray,
                 patch_labels: np.ndarray, chain_offsets: np.ndarray, chain_indices: np.ndarray,
                 chain_patch_offsets: np.ndarray, chain_patch_indices: np.ndarray, corners: np.ndarray,
                 shell_offsets: np.ndarray, shell_indices: np.ndarray, cell_shell_offsets: np.ndarray,
                 cell_shell_indices: np.ndarray, cell_labels: np.ndarray, meta: str) -> None:
    """Writes a result with the command line's writers (ply, plain.ply, obj, vtu, vtm, npz)."""

def remesh(points: np.ndarray, offsets: np.ndarray, indices: np.ndarray, face_patch: np.ndarray,
           face_cells: np.ndarray, face_label: np.ndarray, patches: int, cells: int, chain_offsets: np.ndarray,
           chain_indices: np.ndarray, corners: np.ndarray, cell_volume: np.ndarray, length: float,
           iterations: int = 8) -> dict:
    """A result's polygons remeshed (``Network.remesh``): new arrays, ``report`` and ``embedding`` as JSON text."""

class CutResult:
    """A cut-cell mesh held by the Rust core (wrapped by ``septa.CutCells``)."""
    def summary(self) -> str: ...
    def arrays(self) -> dict: ...
    def write_vtu(self, path: str) -> None: ...
    def write_obj(self, path: str, explode: float = 0.0) -> None: ...
    def write_foam(self, path: str) -> None: ...

def cut(
    vertices: npt.NDArray[np.float64],
    triangles: npt.NDArray[np.int64],
    planes: npt.NDArray[np.float64],
    threads: int = 0,
) -> CutResult:
    """Planar cut-cell mesh (counts, points, faces with loops, cells)."""

def sparse_plan(job: str) -> tuple[int, list[int], bool]:
    """Step 1 of a sparse job (JSON text): (blocks, kept block indices, dense)."""

def sparse_blocks(job: str, indices: list[int]) -> list[bytes]:
    """Step 2: the given blocks' parts of the network, one ``bytes`` each."""

def sparse_finish(job: str, plan: tuple[int, list[int], bool], results: list[bytes]) -> dict:
    """Step 3: merge in block order, topology; the network dict (as ``network``)."""

def sparse_finish_regions(job: str, plan: tuple[int, list[int], bool], results: list[bytes]) -> dict:
    """Step 3 for a scene's region surfaces: numpy arrays (as ``regions``)."""

def sparse_network(job: str, dense: bool = False, threads: int | None = None) -> dict:
    """The whole job in this process (``compute_sparse``, or the dense path)."""

def stream_ply(job: str, path: str, window: int = 0, triangles: bool = False, threads: int | None = None) -> dict:
    """A sparse job's polygons streamed block by block to one PLY (bounded memory)."""

def continuation(
    f: object,
    k: int,
    mode: str,
    resolution: list[int],
    bounds: list[list[float]],
    split: int = 5,
    block: int = 8,
    seeds: list[tuple[float, float, float]] | None = None,
    dense: bool = False,
    threads: int | None = None,
) -> dict:
    """Network of a callable ``f((n, 3)) -> (n, k)`` by continuation from seeds (or a coarse scan)."""

def continuation_seeds(f: object, k: int, job: tuple, seeds: list | None = None) -> list[int]:
    """Seed blocks of a continuation job ``(mode, resolution, bounds, split, block)``."""

def continuation_blocks(f: object, k: int, job: tuple, indices: list[int]) -> list[tuple[bytes, list[int]]]:
    """One search round's blocks: ``(block result bytes, next blocks)`` each."""

def continuation_finish(f: object, k: int, job: tuple, results: list[bytes]) -> dict:
    """The network of a continuation job from its block results."""
