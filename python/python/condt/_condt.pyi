# Type stubs of the native module condt._condt (python/src/*.rs). The docstrings, with examples,
# are the runtime's (`help(condt.reconstruct)`); tests/test_api.py checks that these signatures
# match the module's, as `python -m mypy.stubtest condt._condt` does.
import os
from typing import (
    Any,
    Literal,
    Mapping,
    Optional,
    Protocol,
    Sequence,
    SupportsFloat,
    SupportsIndex,
    Tuple,
    TypedDict,
    Union,
    final,
)

import numpy as np
import numpy.typing as npt

__all__ = [
    "reconstruct",
    "triangulate",
    "read_points",
    "read_points_with_crs",
    "score",
    "snap",
    "Reconstruction",
    "Curve",
    "EdgeStory",
    "Triangulation",
    "__version__",
    "_tile_params",
    "_tile_plan",
    "_run_tile",
    "_gathered_outliers",
    "_gathered_repair_again",
    "_gathered_smoothing_pass",
    "_tile_state",
    "_step_kept",
    "_tests_kept",
    "_component_labels",
    "_gathered_clumps",
    "_gathered_clumps_found",
    "_gathered_tips",
    "_choices_kept",
    "_gathered_gaps",
    "_local_rules_kept",
    "_gathered_local_outliers",
    "_last_edges_kept",
    "_gathered_last_edges",
    "_given_back_standing",
    "_gathered_given_back",
    "_tile_index",
    "_split_edges",
    "_TileState",
    "_TileIndex",
]

__version__: str

_Points = npt.ArrayLike
_Edges = npt.ArrayLike
_Index = npt.NDArray[np.int64]
_Coords = npt.NDArray[np.float64]
# What the keywords take: Python's and numpy's numbers and booleans (a bool is no number).
_Bool = Union[bool, np.bool_]
_Number = SupportsFloat
_InputFormat = Literal["txt", "text", "node", "csv", "tsv", "npy", "geojson", "json", "geojsonl", "geojsons"]

class _AuthorityCRS(Protocol):
    """What ``to_geojson`` takes of a pyproj ``CRS`` (a GeoDataFrame's ``.crs``)."""
    def to_authority(self) -> Optional[Tuple[str, str]]: ...

@final
class Curve:
    @property
    def points(self) -> _Index: ...
    @property
    def closed(self) -> bool: ...
    @property
    def coords(self) -> _Coords: ...
    def __len__(self) -> int: ...
    def __copy__(self) -> Curve: ...
    def __deepcopy__(self, memo: Any) -> Curve: ...

@final
class EdgeStory:
    @property
    def edge(self) -> tuple[int, int]: ...
    @property
    def kept(self) -> bool: ...
    @property
    def ends(self) -> tuple[dict[str, Any], dict[str, Any]]: ...
    @property
    def changes(self) -> list[dict[str, Any]]: ...
    @property
    def text(self) -> str: ...
    def __copy__(self) -> EdgeStory: ...
    def __deepcopy__(self, memo: Any) -> EdgeStory: ...

@final
class Reconstruction:
    @property
    def edges(self) -> _Index: ...
    @property
    def curves(self) -> list[Curve]: ...
    @property
    def unused(self) -> _Index: ...
    # Pairs of points given twice a little apart, (m, 2) (reconstruct warns).
    @property
    def twin_pairs(self) -> _Index: ...
    @property
    def stages(self) -> dict[str, _Index]: ...
    @property
    def passes(self) -> int: ...
    @property
    def timings(self) -> dict[str, float]: ...
    # Rows [i, first]: point i repeats point first, merged into it.
    @property
    def merged(self) -> _Index: ...
    # Where the last run's stages saw the points (moved by smoothing passes).
    @property
    def stage_points(self) -> _Coords: ...
    # A duplicate point is its first point: explain(4, 1) tells of 0-1 when 4 repeats 0.
    def explain(self, i: SupportsIndex, j: SupportsIndex) -> EdgeStory: ...
    # A pyproj CRS is written by its authority's name; PROJJSON is refused.
    def to_geojson(self, *, crs: Union[str, Mapping[str, Any], _AuthorityCRS, None] = None) -> str: ...
    def to_shapely(self) -> Any: ...
    def __len__(self) -> int: ...
    def __copy__(self) -> Reconstruction: ...
    def __deepcopy__(self, memo: Any) -> Reconstruction: ...

@final
class Triangulation:
    @property
    def triangles(self) -> _Index: ...
    @property
    def edges(self) -> _Index: ...
    # Each hull edge once; on collinear points (no triangle) out and back: [0, 1, 2, 3, 2, 1].
    @property
    def hull(self) -> _Index: ...
    @property
    def num_vertices(self) -> int: ...
    def neighbors(self, i: SupportsIndex) -> _Index: ...
    def __len__(self) -> int: ...
    def __copy__(self) -> Triangulation: ...
    def __deepcopy__(self, memo: Any) -> Triangulation: ...

# What `score` returns: a plain dict at run time, typed here for type checkers only.
class _Score(TypedDict):
    exact: bool
    precision: float
    recall: float
    f1: float
    tp: int
    fp: int
    fn: int
    outlier_edges: int
    max_dist: Optional[float]
    rms_dist: Optional[float]
    malformed: Optional[str]
    n_points: int
    n_gt: int
    n_out: int

def reconstruct(
    points: _Points,
    *,
    paper: _Bool = False,
    u: _Number = ...,
    adaptive: _Bool = ...,
    iqr: Optional[_Number] = ...,
    outlier_filter: _Bool = ...,
    outliers_first: _Bool = ...,
    iqr_floor: _Bool = ...,
    repair_again: _Bool = ...,
    local_outliers: _Bool = ...,
    clumps: _Bool = ...,
    confirm_given_back: _Bool = ...,
    close_gaps: _Bool = ...,
    junctions: _Bool = ...,
    crossings: _Bool = ...,
    tips: _Bool = ...,
    spikes: _Bool = ...,
    hooks: _Bool = ...,
    tails: _Bool = ...,
    detours: _Bool = ...,
    smooth: _Bool = ...,
    repair: Literal["needs", "paper", "mutual", "crossing", "off"] = ...,
    manifold_fix: _Bool = ...,
    method: Literal["condt", "nn-crust", "crust"] = ...,
    sequential: _Bool = ...,
) -> Reconstruction: ...
def triangulate(points: _Points) -> Triangulation: ...
# A path is always a file: "-" is the file named "-", not standard input.
def read_points(
    path: Union[str, bytes, os.PathLike[str], os.PathLike[bytes]],
    *,
    columns: Union[str, Tuple[str, str], Sequence[str], None] = ...,
    input_format: Optional[_InputFormat] = ...,
) -> _Coords: ...
def read_points_with_crs(
    path: Union[str, bytes, os.PathLike[str], os.PathLike[bytes]],
    *,
    columns: Union[str, Tuple[str, str], Sequence[str], None] = ...,
    input_format: Optional[_InputFormat] = ...,
) -> Tuple[_Coords, Optional[str]]: ...
def score(points: _Points, output: _Edges, truth: _Edges) -> _Score: ...
def snap(points: _Points, distance: SupportsFloat) -> _Coords: ...

# condt.dask's native half (python/src/tiles.rs); not for direct use.
def _tile_params(**params: Any) -> None: ...
def _tile_plan(points: _Points, **params: Any) -> dict[str, Any]: ...
def _run_tile(
    points: _Points,
    positions: npt.NDArray[np.int64],
    ranks: npt.NDArray[np.int64],
    owned: npt.NDArray[np.bool_],
    boundary: npt.NDArray[np.int64],
    boundary_len: int,
    hull: _Points,
    band: float,
    known: tuple[float, float, float, float],
    bbox: tuple[float, float, float, float],
    reach: int,
    phase: str,
    keep: bool = ...,
    **params: Any,
) -> tuple[str, Optional[list[npt.NDArray[np.int64]]], Optional[_TileState]]: ...
@final
class _TileState:
    """A certified tile's triangulation, kept on its worker between two phases."""
    def __sizeof__(self) -> int: ...
    def __reduce__(
        self,
    ) -> tuple[
        Any,
        tuple[
            npt.NDArray[np.float64],
            npt.NDArray[np.int64],
            npt.NDArray[np.int64],
            npt.NDArray[np.bool_],
        ],
    ]: ...

def _tile_state(
    points: _Points,
    order: npt.NDArray[np.int64],
    positions: npt.NDArray[np.int64],
    owned: npt.NDArray[np.bool_],
) -> _TileState: ...
def _step_kept(
    state: _TileState, given: npt.NDArray[np.int64], step: str, **params: Any
) -> npt.NDArray[np.int64]: ...
def _tests_kept(
    state: _TileState,
    given: npt.NDArray[np.int64],
    labels: npt.NDArray[np.int64],
    step: str,
    status: npt.NDArray[np.uint8] | None = None,
    **params: Any,
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.uint8]]: ...
def _component_labels(n: int, edges: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]: ...
def _gathered_clumps_found(
    n: int, edges: npt.NDArray[np.int64], tests: npt.NDArray[np.uint8]
) -> bool: ...
def _gathered_clumps(
    n: int,
    edges: npt.NDArray[np.int64],
    tests: npt.NDArray[np.uint8],
    choices: npt.NDArray[np.int64],
    tips: npt.NDArray[np.int64],
    joins: npt.NDArray[np.int64],
) -> npt.NDArray[np.int64] | None: ...
def _gathered_tips(
    n: int, edges: npt.NDArray[np.int64], candidates: npt.NDArray[np.int64]
) -> npt.NDArray[np.int64] | None: ...
def _choices_kept(
    state: _TileState, given: npt.NDArray[np.int64], step: str, **params: Any
) -> npt.NDArray[np.int64]: ...
def _gathered_gaps(
    n: int, edges: npt.NDArray[np.int64], choices: npt.NDArray[np.int64]
) -> npt.NDArray[np.int64] | None: ...
def _local_rules_kept(
    state: _TileState,
    given: npt.NDArray[np.int64],
    before: npt.NDArray[np.int64],
    give_back: bool,
    **params: Any,
) -> npt.NDArray[np.int64]: ...
def _gathered_local_outliers(
    n: int,
    edges: npt.NDArray[np.int64],
    tests: npt.NDArray[np.uint8],
    choices: npt.NDArray[np.int64],
    tips: npt.NDArray[np.int64],
    joins: npt.NDArray[np.int64],
) -> npt.NDArray[np.int64] | None: ...
def _last_edges_kept(
    state: _TileState,
    given: npt.NDArray[np.int64],
    before: npt.NDArray[np.int64],
    **params: Any,
) -> npt.NDArray[np.int64]: ...
def _gathered_last_edges(
    n: int, edges: npt.NDArray[np.int64], candidates: npt.NDArray[np.int64]
) -> npt.NDArray[np.int64] | None: ...
@final
class _TileIndex:
    """Which kept tiles hold each point, and where: built once per tiled run."""

def _tile_index(n: int, tiles: list[npt.NDArray[np.int64]]) -> _TileIndex: ...
def _split_edges(index: _TileIndex, edges: npt.NDArray[np.int64]) -> list[npt.NDArray[np.int64]]: ...
def _given_back_standing(
    n: int, edges: npt.NDArray[np.int64], before_local: npt.NDArray[np.int64]
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.uint8]] | None: ...
def _gathered_given_back(
    n: int,
    edges: npt.NDArray[np.int64],
    before_local: npt.NDArray[np.int64],
    tests: npt.NDArray[np.uint8],
) -> npt.NDArray[np.int64] | None: ...
def _gathered_outliers(
    points: _Points, edges: npt.NDArray[np.int64], **params: Any
) -> npt.NDArray[np.int64]: ...
def _gathered_repair_again(
    points: _Points,
    repaired: npt.NDArray[np.int64],
    proximity: npt.NDArray[np.int64],
    **params: Any,
) -> Optional[npt.NDArray[np.int64]]: ...
def _gathered_smoothing_pass(
    points: _Points,
    edges: npt.NDArray[np.int64],
    passes: int,
    previous: Optional[npt.NDArray[np.int64]] = None,
) -> Union[None, npt.NDArray[np.float64], str]: ...
