"""Runs inside freecadcmd with a fresh HOME whose user Mod folder links to an installed
workbench (install_check in workbench_test.py): FreeCAD must have put the workbench on
sys.path by itself, and the workbench must find the installed sfit module with no
PYTHONPATH, no parameter and no SFIT_PYTHONPATH: through the install step's relative path."""
import json
import os
import sys
import traceback

r = {}
try:
    import sfit_freecad.locate as locate
    r["workbench"] = os.path.dirname(os.path.dirname(os.path.abspath(locate.__file__)))
    sfit = locate.find_sfit()
    r["sfit"] = os.path.abspath(sfit.__file__)
    r["version"] = sfit.__version__
    r["sys_path_has_mod"] = any(p.rstrip("/").endswith("Mod/Sfit") for p in sys.path)
except Exception:  # noqa: BLE001
    r["error"] = traceback.format_exc()
with open(os.environ["SFIT_RESULT"], "w") as f:
    json.dump(r, f)
