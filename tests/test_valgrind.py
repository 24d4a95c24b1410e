"""Memory check of the Release build under valgrind (memcheck), 1 rank, without mpirun: small
scenes (an FE body on a kinematic plane; an FE body, a rigid ball and a kinematic plane; a rigid
body shaped by a tet mesh on an elastic slab with the fast scheme) run a few steps with
--leak-check=full and XML output.

OpenMPI, hwloc, PMIx and PETSc keep memory alive at exit and touch uninitialised bytes of their
own; that noise is not ours. Rather than a suppression file (tied to library versions), the XML
is parsed and a record fails the test only when its stack holds a fecontact frame (a frame in
the fecontact binary, which links libfecontact.a statically, or a source file under src/), and no
frame of the libraries' own start-up or shut-down (PetscInitialize/PetscFinalize, MPI_Init/
MPI_Finalize, which main calls):
  - invalid read/write/free, mismatched free, overlapping copy, fishy value, bad jump;
  - use of uninitialised values (conditional jump, value, syscall parameter);
  - definitely or indirectly lost blocks (possibly lost and still reachable are PETSc's and
    OpenMPI's caches: not reported by --show-leak-kinds).
Every other record is counted and shown as noise. Usage: test_valgrind.py [--np 1]"""
import os
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

from fctest import EXE, ROOT, ENV, TMP, Checker

c = Checker("valgrind")
VALGRIND = shutil.which("valgrind")
if not VALGRIND:
    print("valgrind not found (apt-get install valgrind, scripts/setup.sh): skipped")
    sys.exit(0)

EXE_REAL = os.path.realpath(EXE)
SRC_DIR = os.path.join(ROOT, "src")
FAIL_KINDS = ("InvalidRead", "InvalidWrite", "InvalidFree", "MismatchedFree", "Overlap", "FishyValue",
              "InvalidJump", "InvalidMemPool", "UninitCondition", "UninitValue", "SyscallParam",
              "Leak_DefinitelyLost", "Leak_IndirectlyLost")

SCENES = [
    ("cube_drop (fem + kinematic plane)",
     ["-options_file", "input/cube_drop.opts", "-time_steps", "3"]),
    ("default, coarse cube (fem + rigid sphere + kinematic plane)",
     ["-options_file", "input/default.opts", "-cube_dm_plex_filename", "meshes/cube_coarse.msh", "-time_steps", "3"]),
    ("mesh_on_slab, fast scheme (rigid mesh shape + fem slab + kinematic)",
     ["-options_file", "input/mesh_on_slab.opts", "-slab_dm_plex_filename", "meshes/cube_coarse.msh",
      "-block_translate", "0,0,1.01", "-time_steps", "2", "-constraint_scheme", "fast"]),
]


def frames(err):
    for f in err.iter("frame"):
        yield {k: (f.findtext(k) or "") for k in ("obj", "fn", "dir", "file", "line")}


# The libraries' own start-up and shut-down, called from main: their records are noise
LIFECYCLE = ("PetscInitialize", "PetscFinalize", "PMPI_Init", "PMPI_Init_thread", "PMPI_Finalize", "MPI_Init",
             "MPI_Init_thread", "MPI_Finalize", "ompi_mpi_init", "ompi_mpi_finalize")


def lifecycle(err):
    return any(fr["fn"] in LIFECYCLE for fr in frames(err))


def ours(fr):
    if fr["obj"] and os.path.realpath(fr["obj"]) == EXE_REAL:
        return True
    d = os.path.realpath(fr["dir"]) if fr["dir"] else ""
    return d == SRC_DIR or d.startswith(SRC_DIR + os.sep)


def describe(err):
    what = err.findtext("what") or (err.find("xwhat").findtext("text") if err.find("xwhat") is not None else "")
    lines = ["  %s: %s" % (err.findtext("kind"), what)]
    for fr in list(frames(err))[:20]:
        where = "%s:%s" % (fr["file"], fr["line"]) if fr["file"] else os.path.basename(fr["obj"])
        lines.append("    %s%s (%s)" % ("* " if ours(fr) else "  ", fr["fn"] or "???", where))
    return "\n".join(lines)


def scene_options(label, args):
    """The scene files name their bodies; place every output in the temporary directory."""
    return args + ["-output_file", os.path.join(TMP, "vg_%d.h5" % abs(hash(label))), "-quiet"]


for label, args in SCENES:
    xml = os.path.join(TMP, "vg_%d.xml" % abs(hash(label)))
    cmd = [VALGRIND, "--tool=memcheck", "--leak-check=full", "--show-leak-kinds=definite,indirect",
           "--errors-for-leak-kinds=definite,indirect", "--num-callers=40", "--error-exitcode=99",
           "--xml=yes", "--xml-file=" + xml, EXE] + scene_options(label, args)
    t = time.time()
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=1200)
    wall = time.time() - t
    if p.returncode not in (0, 99):
        sys.stderr.write(p.stdout[-4000:] + p.stderr[-4000:])
    c.check(p.returncode in (0, 99), "%s: fecontact ran to the end under valgrind (exit %d, %.0f s)" % (label, p.returncode, wall))
    try:
        root = ET.parse(xml).getroot()
    except (ET.ParseError, FileNotFoundError) as e:
        c.check(False, "%s: valgrind XML readable (%s)" % (label, e))
        continue
    bad, noise = [], {}
    for err in root.iter("error"):
        kind = err.findtext("kind")
        if kind in FAIL_KINDS and not lifecycle(err) and any(ours(fr) for fr in frames(err)):
            bad.append(err)
        else:
            noise[kind] = noise.get(kind, 0) + 1
    for err in bad:
        print(describe(err))
    c.check(not bad, "%s: %d records with a fecontact frame (invalid access, uninitialised use, definite or "
            "indirect leak); %d noise records outside fecontact %s" % (label, len(bad), sum(noise.values()),
                                                                      dict(sorted(noise.items()))))

c.done()
