"""sfit in FreeCAD: the headless core (rows, feature) and the GUI (gui, loaded only with
FreeCAD's GUI). See docs/freecad.md of the sfit repository."""
