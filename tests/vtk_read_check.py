#!/usr/bin/env python3
"""VTK itself reads what `sablier run` writes.

Runs a tiny bed2d twice (plain and --compress, both with --grid and CSV
frames), then reads every frame the series list with VTK's own readers
(vtkXMLPolyDataReader, vtkXMLImageDataReader) and checks point counts,
array names and values against the CSV frames. Any error or warning VTK
reports fails the check. Without VTK's Python modules (Debian:
python3-vtk9, which scripts/setup.sh installs) the check FAILS rather than
passing unseen.

Usage: vtk_read_check.py SABLIER_BINARY SCENES_DIR WORK_DIR
"""
import csv
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

try:
    from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader
except ImportError as error:
    sys.exit(f"FAIL: cannot import VTK's Python modules with {sys.executable} ({error}); "
             "install python3-vtk9 (bash scripts/setup.sh does)")

# 64 x 32 cells of 1/64 m, sand filling the box at 2 x 2 particles per
# cell (set here: bed2d.toml seeds 3 per axis): 8192 particles, so that
# 3-component Float64 arrays fill exactly three 64 KiB zlib blocks (the
# header's "last block size" is then 0) and the 9-component stress spans
# nine.
CELLS = (64, 32)
H = 1.0 / 64
PARTICLES = 8192
POINT_ARRAYS = {"velocity", "volume", "pressure", "phi", "stress", "shear_rate", "id", "material"}
GRID_ARRAYS = {"phi", "velocity", "pressure", "active", "regime"}

# Every message VTK emits (errors, warnings) lands here instead of stderr.
MESSAGES = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(MESSAGES)


def check(condition, what):
    if not condition:
        sys.exit(f"FAIL: {what}")


def read(reader_class, path):
    reader = reader_class()
    reader.SetFileName(path)
    reader.Update()
    messages = MESSAGES.GetOutput()
    check(not messages, f"VTK reported trouble reading {path}:\n{messages}")
    return reader.GetOutput()


def run(sablier, scenes, out, extra):
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sablier, "run", os.path.join(scenes, "bed2d.toml"), "--out", out,
           "--set", "time.frames=2", "--set", f"grid.resolution=[{CELLS[0]},{CELLS[1]}]",
           "--set", "sand.0.max=[1.0,0.5]", "--set", "sand.0.particles_per_cell=2",
           "--format", "vtp,csv", "--grid",
           "--threads", "1", "--quiet"] + extra
    result = subprocess.run(cmd, capture_output=True, text=True)
    check(result.returncode == 0, f"{' '.join(cmd)} exited {result.returncode}:\n{result.stderr}")


def series(path):
    """(time, file) of each DataSet of a .pvd: VTK 9.1 has no PVD reader
    (vtkPVDReader is ParaView's), so the collection is parsed here and each
    entry read with VTK."""
    root = ET.parse(path).getroot()
    check(root.get("type") == "Collection", f"{path}: not a VTK collection")
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def field_value(data, name):
    array = data.GetFieldData().GetArray(name)
    check(array is not None and array.GetNumberOfTuples() == 1, f"field data {name} missing")
    return array.GetValue(0)


def check_particles(path, time, rows):
    poly = read(vtkXMLPolyDataReader, path)
    n = poly.GetNumberOfPoints()
    check(n == len(rows) == PARTICLES, f"{path}: {n} points, CSV {len(rows)} rows")
    check(poly.GetNumberOfVerts() == n, f"{path}: {poly.GetNumberOfVerts()} vertices")
    check(field_value(poly, "TIME") == time, f"{path}: TIME differs from the series' {time}")
    check(field_value(poly, "DIMENSION") == 2, f"{path}: DIMENSION")
    pd = poly.GetPointData()
    names = {pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())}
    check(names == POINT_ARRAYS, f"{path}: point arrays {sorted(names)}")
    velocity, stress = pd.GetArray("velocity"), pd.GetArray("stress")
    ids = set()
    for p, row in enumerate(rows):
        x, y, z = poly.GetPoint(p)
        vx, vy, vz = velocity.GetTuple3(p)
        s = stress.GetTuple9(p)
        ours = [x, y, vx, vy, pd.GetArray("volume").GetValue(p),
                pd.GetArray("pressure").GetValue(p), pd.GetArray("phi").GetValue(p),
                s[0], s[4], s[1]]
        # CSV values are the shortest text that reads back to the same double.
        check(ours == [float(v) for v in row] and z == vz == 0.0 and s[1] == s[3],
              f"{path}: particle {p} differs from the CSV row {row}: {ours}")
        ids.add(pd.GetArray("id").GetValue(p))
        check(pd.GetArray("material").GetValue(p) == 0, f"{path}: material of particle {p}")
    check(ids == set(range(n)), f"{path}: ids are not 0..{n - 1}")


def node_volume(i, j):
    v = H * H
    if i in (0, CELLS[0]):
        v /= 2
    if j in (0, CELLS[1]):
        v /= 2
    return v


def check_grid(path, time, grain_volume, first):
    image = read(vtkXMLImageDataReader, path)
    nx, ny = CELLS[0] + 1, CELLS[1] + 1
    check(image.GetDimensions() == (nx, ny, 1), f"{path}: dimensions {image.GetDimensions()}")
    check(image.GetSpacing() == (H, H, H), f"{path}: spacing {image.GetSpacing()}")
    check(image.GetOrigin() == (0.0, 0.0, 0.0), f"{path}: origin {image.GetOrigin()}")
    check(field_value(image, "TIME") == time, f"{path}: TIME differs from the series' {time}")
    pd = image.GetPointData()
    names = {pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())}
    check(names == GRID_ARRAYS, f"{path}: point arrays {sorted(names)}")
    check(pd.GetArray("velocity").GetNumberOfComponents() == 3, f"{path}: velocity components")
    for name in ("active", "regime"):
        check(pd.GetArray(name).GetDataTypeAsString() == "unsigned char", f"{path}: {name} type")
    phi, pressure, active, regime = (pd.GetArray(a) for a in ("phi", "pressure", "active", "regime"))
    total, actives = 0.0, 0
    for j in range(ny):
        for i in range(nx):
            n = j * nx + i  # x fastest, as VTK orders ImageData points
            total += phi.GetValue(n) * node_volume(i, j)
            # 0: no stress row; 1-3: separated, sticking, sliding.
            check((regime.GetValue(n) != 0) == bool(active.GetValue(n)) and regime.GetValue(n) <= 3,
                  f"{path}: node {i},{j} regime {regime.GetValue(n)}")
            if active.GetValue(n):
                actives += 1
            else:
                check(pressure.GetValue(n) == 0.0 and pd.GetArray("velocity").GetTuple3(n) ==
                      (0.0, 0.0, 0.0), f"{path}: inactive node {i},{j} has values")
    # Grain volume per node sums to the particles' (partition of unity).
    check(abs(total - grain_volume) <= 1e-9 * grain_volume,
          f"{path}: sum of phi V_i = {total}, particles hold {grain_volume}")
    check(actives == (0 if first else nx * ny), f"{path}: {actives} active nodes")
    if not first:
        floor = sum(pressure.GetValue(i) for i in range(nx)) / nx
        check(floor > 0.0, f"{path}: no pressure at the floor")


def check_run(out, compressed):
    frames = series(os.path.join(out, "series.pvd"))
    grids = series(os.path.join(out, "grid_series.pvd"))
    check(len(frames) == len(grids) == 3, f"{out}: series list {len(frames)}, {len(grids)} frames")
    for k, ((time, vtp), (grid_time, vti)) in enumerate(zip(frames, grids)):
        check(time == grid_time, f"{out}: frame {k} times differ")
        for name in (vtp, vti):
            with open(os.path.join(out, name), "rb") as f:
                head = f.read(400)
            check((b'compressor="vtkZLibDataCompressor"' in head) == compressed,
                  f"{name}: compressed should be {compressed}")
        with open(os.path.join(out, vtp[:-4] + ".csv"), newline="") as f:
            rows = list(csv.reader(f))[1:]
        check_particles(os.path.join(out, vtp), time, rows)
        grain_volume = sum(float(r[4]) for r in rows)
        check_grid(os.path.join(out, vti), time, grain_volume, k == 0)


def check_bodies(sablier, scenes, work, scene, dimension):
    """The rigid bodies' frames (frames/bodies_NNNNN.vtp, bodies_series.pvd):
    VTK reads them, a box is its 4 (2D, one closed line) or 8 corners (3D,
    six polygons), and their mean is the centre bodies.csv gives for that
    frame's time."""
    out = os.path.join(work, scene)
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sablier, "run", os.path.join(scenes, scene + ".toml"), "--out", out,
           "--set", "time.frames=2", "--threads", "1", "--quiet"]
    result = subprocess.run(cmd, capture_output=True, text=True)
    check(result.returncode == 0, f"{' '.join(cmd)} exited {result.returncode}:\n{result.stderr}")
    with open(os.path.join(out, "bodies.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    entries = series(os.path.join(out, "bodies_series.pvd"))
    check(len(entries) == 3, f"{out}: bodies series of {len(entries)} frames")
    axes = "xyz"[:dimension]
    for k, (time, name) in enumerate(entries):
        poly = read(vtkXMLPolyDataReader, os.path.join(out, name))
        n = poly.GetNumberOfPoints()
        cells = poly.GetNumberOfLines() if dimension == 2 else poly.GetNumberOfPolys()
        check(n == 2 ** dimension and cells == (1 if dimension == 2 else 6),
              f"{name}: {n} points, {cells} cells")
        index = poly.GetCellData().GetArray("obstacle")
        check(index is not None and index.GetValue(0) == 0, f"{name}: obstacle index")
        mean = [sum(poly.GetPoint(p)[a] for p in range(n)) / n for a in range(dimension)]
        if k == 0:
            continue  # the scene's start, before the first row
        row = [r for r in rows if abs(float(r["time"]) - time) <= 1e-12][-1]
        centre = [float(row[a]) for a in axes]
        check(all(abs(m - c) <= 1e-12 for m, c in zip(mean, centre)),
              f"{name}: corners centred at {mean}, bodies.csv says {centre}")
    shutil.rmtree(out)


def check_moving_solid(sablier, scenes, work):
    """A solid driven into the sand (plough3d's blade) in the bodies' frames:
    VTK reads it, a box of 8 corners and 6 faces, moved by its velocity
    times the frame's time from where the scene puts it."""
    out = os.path.join(work, "plough3d")
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sablier, "run", os.path.join(scenes, "plough3d.toml"), "--out", out,
           "--set", "time.frames=2", "--threads", "1", "--quiet"]
    result = subprocess.run(cmd, capture_output=True, text=True)
    check(result.returncode == 0, f"{' '.join(cmd)} exited {result.returncode}:\n{result.stderr}")
    entries = series(os.path.join(out, "bodies_series.pvd"))
    check(len(entries) == 3, f"{out}: bodies series of {len(entries)} frames")
    for time, name in entries:
        poly = read(vtkXMLPolyDataReader, os.path.join(out, name))
        n = poly.GetNumberOfPoints()
        check(n == 8 and poly.GetNumberOfPolys() == 6, f"{name}: {n} points")
        low = min(poly.GetPoint(p)[0] for p in range(n))
        # The blade's min x is 0.04 m at 0 s and it moves at 0.15 m/s.
        check(abs(low - (0.04 + 0.15 * time)) <= 1e-12, f"{name}: blade at x = {low} at {time} s")
    shutil.rmtree(out)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    sablier, scenes, work = sys.argv[1:]
    for name, extra in (("plain", []), ("zlib", ["--compress"])):
        out = os.path.join(work, name)
        run(sablier, scenes, out, extra)
        check_run(out, extra == ["--compress"])
        shutil.rmtree(out)
    check_bodies(sablier, scenes, work, "crate2d", 2)
    check_bodies(sablier, scenes, work, "crate3d", 3)
    check_moving_solid(sablier, scenes, work)
    print("ok: VTK read the particle, grid, body and moving-solid frames and series, plain and compressed")


if __name__ == "__main__":
    main()
