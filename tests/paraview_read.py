"""Run by pvbatch (tests/test_paraview.py): opens an fecontact .xmf with ParaView's readers and saves
what they read at some times, for the test to compare with h5py.
Usage: pvbatch paraview_read.py FILE.xmf OUT.npz TIME [TIME ...]
Readers: 'default' (what File > Open picks: OpenDataFile) and 'xdmf2' (the "XDMF Reader").
Saved per reader r, time index i, leaf j (in the order of the XDMF grids, empty grids have no leaf):
  r/times                      the reader's time steps
  r/i/names                    leaf names (XDMF Reader with several grids only; '' otherwise)
  r/i/j/points, r/i/j/ncells, r/i/j/point/<array>, r/i/j/cell/<array>
Prints nothing itself: anything on stdout or stderr comes from ParaView (the test fails on it)."""
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import OpenDataFile, XDMFReader
from vtkmodules.util.numpy_support import vtk_to_numpy

xmf, npz = os.path.abspath(sys.argv[1]), sys.argv[2]  # the Xdmf3 readers need an absolute path
times = [float(t) for t in sys.argv[3:]]
saved = {}
for rname, make in [("default", lambda: OpenDataFile(xmf)), ("xdmf2", lambda: XDMFReader(FileNames=[xmf]))]:
    r = make()
    r.UpdatePipelineInformation()
    saved[rname + "/times"] = np.array(r.TimestepValues, dtype=float)
    saved[rname + "/class"] = np.array(r.GetXMLName())
    for i, t in enumerate(times):
        r.UpdatePipeline(t)
        d = servermanager.Fetch(r)
        if d.IsA("vtkCompositeDataSet"):
            leaves = []
            it = d.NewIterator()
            it.InitTraversal()
            while not it.IsDoneWithTraversal():
                meta = it.GetCurrentMetaData()
                leaves.append((it.GetCurrentDataObject(), meta.Get(d.NAME()) if meta and meta.Has(d.NAME()) else ""))
                it.GoToNextItem()
        else:  # one grid (a scene of one body without contacts): the dataset itself, no name
            leaves = [(d, "")]
        names = []
        for j, (b, name) in enumerate(leaves):
            names.append(name)
            key = "%s/%d/%d/" % (rname, i, j)
            pts = b.GetPoints()
            saved[key + "points"] = vtk_to_numpy(pts.GetData()) if pts else np.zeros((0, 3))
            saved[key + "ncells"] = np.array(b.GetNumberOfCells())
            for where, data in [("point", b.GetPointData()), ("cell", b.GetCellData())]:
                for a in range(data.GetNumberOfArrays()):
                    arr = data.GetArray(a)
                    if arr is not None:
                        saved[key + where + "/" + arr.GetName()] = vtk_to_numpy(arr)
        saved["%s/%d/names" % (rname, i)] = np.array(names)
np.savez(npz, **saved)
