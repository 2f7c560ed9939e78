"""`import vis4gs` re-exports every wrapped module named on the command line."""
import importlib
import sys

import vis4gs

failures = []
for module in sys.argv[1:]:
    library = module.replace("Vis4GS::", "vis4gs")
    sub = importlib.import_module("vis4gs." + library)
    exported = [name for name in dir(sub) if name.startswith("vtk")]
    missing = [name for name in exported if getattr(vis4gs, name, None) is not getattr(sub, name)]
    if missing:
        failures.append("%s: not re-exported by vis4gs: %s" % (library, ", ".join(missing)))
if not sys.argv[1:]:
    failures.append("no module names given")
if not vis4gs.__version__:
    failures.append("vis4gs.__version__ is empty")
for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
