#!/usr/bin/python3
"""docs/options.md against the options the code reads: every option named in src/ is documented
there, every option documented there is read by src/ (or passed on to PETSc, which reads it), and
the default a table row gives is the one the code starts from, as `-help` prints it ("<now X :
formerly D>" or "<X : D>": D is the value before the options database was read) on a set of
scenes that read, between them, most options."""
import glob
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fctest as T  # noqa: E402

c = T.Checker("options doc")
DOC = open(os.path.join(T.ROOT, "docs", "options.md")).read()

# options named in the sources: string literals "-name" (with a prefix, "-<body>_name")
src = ""
for f in sorted(glob.glob(os.path.join(T.ROOT, "src", "**", "*.c"), recursive=True)):
    src += open(f).read()
read = set(re.findall(r'"-([a-z][a-z0-9_]*)"', src))
# PETSc's own options that the code looks up only to report or forward them
PETSC_OWN = {"options_file", "options_file_yaml"}
# PETSc options docs/options.md documents for a body's prefix: PETSc reads them (KSP, PC, SNES, MUMPS, DMPlex, partitioner)
PETSC_READ = re.compile(r"^(ksp_|pc_|snes_|mat_mumps_|dm_|petscpartitioner_)")


def documented(o):
    return re.search(r"`-%s\b" % re.escape(o), DOC) or re.search(r"-<name>_%s\b" % re.escape(o), DOC)


missing = sorted(o for o in read - PETSC_OWN if not documented(o))
c.check(not missing, "every option read in src/ is in docs/options.md (%d options; missing: %s)"
        % (len(read - PETSC_OWN), ", ".join("-" + o for o in missing) or "none"))

# the options of the tables (first cell of each row) and their defaults (the column "default" of the table)
rows = {}
col = None
for line in DOC.splitlines():
    cells = [x.strip() for x in re.split(r"(?<!\\)\|", line.strip().strip("|"))]  # "\|" inside a cell
    if line.startswith("| option |"):
        col = cells.index("default") if "default" in cells else None
        continue
    if not line.startswith("| `-"):
        if not line.startswith("|"):
            col = None
        continue
    for m in re.finditer(r"`-(?:<name>_)?([a-z][a-z0-9_]*)", cells[0]):
        rows.setdefault(m.group(1), []).append(cells[col] if col is not None and col < len(cells) else "")
unread = sorted(o for o in rows if o not in read and not PETSC_READ.match(o))
c.check(not unread, "every option of docs/options.md's tables is read in src/ (%d options; not read: %s)"
        % (len(rows), ", ".join("-" + o for o in unread) or "none"))

# defaults: -help on scenes that between them read most options
SCENES = [
    ["-options_file", "input/cube_fall.opts"],
    ["-options_file", "input/two_cubes.opts", "-constraint_scheme", "standard"],
    ["-options_file", "input/table1_18k.opts", "-constraint_scheme", "fast", "-pgs_ranks", "auto"],
    ["-options_file", "input/rolling.opts"],
    ["-options_file", "input/grasp_rotate.opts", "-compliance_type", "redundant"],
    ["-options_file", "input/box_on_slab.opts", "-compliance_type", "inverse", "-pgs_dump_problem",
     os.path.join(T.TMP, "p.h5")],
    ["-options_file", "input/sliding.opts"],
    ["-options_file", "input/membrane.opts", "-compliance_type", "condensed"],
]
# PETSc 3.18's -help: reals "<current : default>", bools "name: <default : current>", ints and strings
# "<now current : formerly default>" (a string read into the buffer that held its default shows the value
# read twice: such a line is skipped where the scene sets the option)
HELP = re.compile(r"^\s+-([a-z][a-z0-9_]*)(:?) <(?:now (.*?) : formerly (.*?)|([^<>:]*?) : ([^<>]*?))>")


def norm(v):
    v = v.strip().strip("`").strip()
    low = v.lower()
    if low in ("true", "yes"):
        return 1.0
    if low in ("false", "no"):
        return 0.0
    try:
        return float(v)
    except ValueError:
        return v


def same(a, b):
    a, b = norm(a), norm(b)
    if isinstance(a, float) and isinstance(b, float):
        return abs(a - b) <= 1e-12 * max(abs(a), abs(b))
    return a == b


seen, wrong = {}, []
for args in SCENES:
    p = T.run(args + ["-time_steps", "1", "-help", "-quiet", "-output_file", os.path.join(T.TMP, "h.h5")], check=False)
    c.check(p.returncode == 0, "-help on %s runs (exit %d)" % (" ".join(args), p.returncode))
    given = " ".join(args) + " -time_steps -quiet -output_file " + open(os.path.join(T.ROOT, args[1])).read()
    bodies = []
    m = re.search(r"-scene_bodies <(?:now )?([a-z0-9_,]+)", p.stdout)
    if m:
        bodies = m.group(1).split(",")
    for line in p.stdout.splitlines():
        h = HELP.match(line)
        if not h:
            continue
        full = name = h.group(1)
        if h.group(3) is not None:
            if h.group(3) == h.group(4) and re.search(r"-%s\b" % full, given):
                continue
            default = h.group(4)
        else:
            default = h.group(5) if h.group(2) else h.group(6)
        for b in bodies:
            if name.startswith(b + "_"):
                name = name[len(b) + 1:]
                break
        if name not in rows or default.strip() == "":
            continue
        simple = [d for d in rows[name] if re.fullmatch(r"`[^`]*`( \(.*\))?|[-+0-9.eE]+|true|false", d.strip())]
        if not simple:
            continue
        seen[name] = default
        if not any(same(d.split(" (")[0], default) for d in simple):
            wrong.append("-%s: code %s, docs %s" % (full, default, " / ".join(simple)))
wrong = sorted(set(wrong))
c.check(len(seen) >= 40, "-help printed the defaults of %d documented options (at least 40)" % len(seen))
c.check(not wrong, "each of them is the default docs/options.md gives (%d checked; differing: %s)"
        % (len(seen), "; ".join(wrong) or "none"))
c.done()
