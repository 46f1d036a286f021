# sfit workbench: nothing to set up without the GUI. The headless core is the package
# sfit_freecad (feature.create, rows); FreeCAD has put this folder on sys.path.
