"""Finds the sfit Python module for FreeCAD, whose interpreter does not see PYTHONPATH when
started from a desktop menu.

Tried in order, the first that imports wins:
  1. ``import sfit`` as FreeCAD's Python already sees it (a .deb or pip install under /usr);
  2. the directory in the FreeCAD parameter
     ``User parameter:BaseApp/Preferences/Mod/Sfit/ModulePath`` (a build tree's
     ``build/python``, or any folder holding the package ``sfit``);
  3. the directory in the environment variable ``SFIT_PYTHONPATH``;
  4. the directory the install step put the module in, relative to this workbench
     (``_install_paths.py``, written by CMake at install time).
"""
import importlib
import os
import sys

PARAMETER_GROUP = "User parameter:BaseApp/Preferences/Mod/Sfit"


def _candidates():
    try:
        import FreeCAD
        path = FreeCAD.ParamGet(PARAMETER_GROUP).GetString("ModulePath", "")
        if path:
            yield path, "the FreeCAD parameter Mod/Sfit/ModulePath"
    except ImportError:
        pass
    if os.environ.get("SFIT_PYTHONPATH"):
        yield os.environ["SFIT_PYTHONPATH"], "SFIT_PYTHONPATH"
    try:
        from . import _install_paths
        here = os.path.dirname(os.path.realpath(__file__))  # through a linked Mod folder
        yield (os.path.normpath(os.path.join(here, _install_paths.PYTHON_DIR_FROM_PACKAGE)),
               "the install step's module folder")
    except ImportError:
        pass


def find_sfit():
    """Returns the module sfit, or raises ImportError saying where it was looked for."""
    try:
        return importlib.import_module("sfit")
    except ImportError:
        pass
    tried = ["FreeCAD's sys.path"]
    for path, why in _candidates():
        tried.append(f"{path} ({why})")
        if os.path.isdir(os.path.join(path, "sfit")) and path not in sys.path:
            sys.path.insert(0, path)
            try:
                return importlib.import_module("sfit")
            except ImportError:
                sys.path.remove(path)
    raise ImportError("the sfit Python module was not found; looked in: " + "; ".join(tried) +
                      ". Install sfit (its .deb, cmake --install, or pip install .), or set "
                      "the parameter Mod/Sfit/ModulePath to a build's python folder "
                      "(docs/freecad.md)")
