"""GIS layers (a GIS analyst's review with GeoPandas): shapely geometries refused with the fix
named, a pyproj CRS written as GeoJSON's crs member and PROJJSON refused, a file in longitudes
and latitudes warned of, and python/README.md's *GeoPandas* recipe run as written."""

import io
import json
import math
import warnings

import numpy as np
import pytest

import condt
from conftest import DATA

shapely = pytest.importorskip("shapely")


def ring(n=40, x0=560_000.0, y0=6_650_000.0, r=50.0):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([x0 + r * np.cos(t), y0 + r * np.sin(t)])


@pytest.mark.parametrize(
    "wrap",
    [
        lambda pts: list(shapely.points(pts)),
        lambda pts: shapely.points(pts),  # an object array, as GeoSeries.values gives
        lambda pts: np.column_stack([shapely.points(pts), np.zeros(len(pts))]),
    ],
    ids=["list", "array", "table"],
)
def test_shapely_geometries_are_refused_naming_get_coordinates(wrap):
    # It was "float() argument must be a string or a real number, not 'Point'": no word of the
    # points or of the coordinates wanted.
    with pytest.raises(TypeError, match=r"shapely geometries \(Point\).*get_coordinates"):
        condt.reconstruct(wrap(ring()))


def test_one_shapely_geometry_is_refused_naming_its_coordinates():
    with pytest.raises(TypeError, match=r"not MultiPoint \(a shapely geometry: pass shapely"):
        condt.reconstruct(shapely.MultiPoint(ring()))
    # The fix named works: the coordinates give the ring.
    r = condt.reconstruct(shapely.get_coordinates(shapely.MultiPoint(ring())))
    assert [c.closed for c in r.curves] == [True] and len(r.curves[0]) == 40


def test_a_geoseries_and_a_geodataframe_are_refused_naming_get_coordinates():
    gpd = pytest.importorskip("geopandas")
    points = gpd.GeoDataFrame(
        {"name": ["a"] * 40}, geometry=gpd.points_from_xy(*ring().T), crs="EPSG:32632"
    )
    for given in (points, points.geometry, points.geometry.values):
        with pytest.raises(TypeError, match="gdf.get_coordinates"):
            condt.reconstruct(given)


def test_a_pyproj_crs_is_written_by_its_authority_and_read_back_as_given():
    pyproj = pytest.importorskip("pyproj")
    r = condt.reconstruct(ring())
    for crs, name in [
        (pyproj.CRS("EPSG:32632"), "urn:ogc:def:crs:EPSG::32632"),
        (pyproj.CRS("OGC:CRS84"), "OGC:CRS84"),
    ]:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # a crs given: no warning of metres without one
            doc = json.loads(r.to_geojson(crs=crs))
        assert doc["crs"] == {"type": "name", "properties": {"name": name}}
        assert pyproj.CRS(name) == crs
    custom = pyproj.CRS("+proj=tmerc +lat_0=0 +lon_0=9.5 +k=1 +x_0=0 +y_0=0 +ellps=GRS80")
    assert custom.to_authority() is None
    with pytest.raises(ValueError, match="no authority code"):
        r.to_geojson(crs=custom)


def test_projjson_is_refused_where_gdal_would_read_it_as_degrees():
    pyproj = pytest.importorskip("pyproj")
    r = condt.reconstruct(ring())
    crs = pyproj.CRS("EPSG:32632")
    for given in (crs.to_json(), crs.to_json_dict()):
        with pytest.raises(ValueError, match=r"PROJJSON .*gdf\.crs"):
            r.to_geojson(crs=given)
    # GeoJSON 2008's own crs objects are written as given, as before.
    named = {"type": "name", "properties": {"name": "EPSG:32632"}}
    assert json.loads(r.to_geojson(crs=named))["crs"] == named


def test_geodataframe_lines_round_trip_the_input_coordinates_exactly():
    gpd = pytest.importorskip("geopandas")
    points = condt.read_points(DATA / "shapes.txt") * 1000.0 + (560_000.0, 6_650_000.0)
    r = condt.reconstruct(points)
    back = gpd.read_file(io.StringIO(r.to_geojson(crs="EPSG:32632")))
    assert back.crs == "EPSG:32632" and len(back) == len(r.curves)
    for line, curve in zip(back.geometry, r.curves):
        xy = np.asarray(line.coords)
        assert np.array_equal(xy[: len(curve)], points[curve.points])  # the same doubles
        assert line.is_closed == curve.closed and line.is_valid
        assert not (np.diff(xy, axis=0) == 0).all(axis=1).any()  # no vertex twice in a row


def lon_lat_file(tmp_path, lat, name="ll.csv", header="lon,lat"):
    t = np.linspace(0, 2 * np.pi, 30, endpoint=False)
    rows = "".join(f"{10 + 0.01 * math.cos(a)!r},{lat + 0.005 * math.sin(a)!r}\n" for a in t)
    path = tmp_path / name
    path.write_text(f"{header}\n{rows}")
    return path


@pytest.mark.parametrize("lat", [60.0, -45.0])
def test_read_points_warns_of_longitudes_and_latitudes_away_from_the_equator(tmp_path, lat):
    # The command line noted it; read_points said nothing (a GIS analyst's review).
    farthest = abs(lat) + 0.005
    stretch = f"{1 / math.cos(math.radians(farthest)):.1f} times"
    with pytest.warns(UserWarning, match=rf"at latitude {farthest:.0f}, .*{stretch}.*to_crs"):
        condt.read_points(lon_lat_file(tmp_path, lat))


def test_read_points_is_silent_near_the_equator_and_on_projected_metres(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        condt.read_points(lon_lat_file(tmp_path, 10.0))
        # x and y columns say nothing of degrees, whatever the values.
        condt.read_points(lon_lat_file(tmp_path, 60.0, name="xy.csv", header="x,y"))


def test_the_readmes_geopandas_recipe_runs_as_written():
    """python/README.md's *GeoPandas* block: its asserts check the three borders against the
    lines the points were sampled from, and the two fields' areas."""
    pytest.importorskip("geopandas")
    from test_api import run_the_readmes_first_block_under

    names = run_the_readmes_first_block_under("## GeoPandas")
    lines, points = names["lines"], names["points"]
    # Every id names a point of the layer, none of the geometries without a point.
    ids = {i for row in lines.point_ids for i in row}
    assert ids <= set(points.index)
    none, empty, junctions = points.index[-3:]
    assert none not in ids and empty not in ids
    # The MultiPoint holds both junctions: every border starts and ends at one of them.
    assert all(row[0] == junctions and row[-1] == junctions for row in lines.point_ids)
