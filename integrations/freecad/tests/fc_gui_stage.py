"""Runs inside FreeCAD's GUI (started by gui_test.py under Xvfb, the workbench installed in the
user Mod folder of a fresh HOME): the sections drawn, selected in order, the command
"Fit surface" run as a user clicks it; records what the GUI shows (the task panel open, its
report, the deviation display) and saves a screenshot of the window with the task panel and
the fitted face (Qt's grab of the window, the 3D view drawn into it by saveImage, which
renders off-screen where Xvfb's GL widget grabs black). The job: a JSON file named by
SFIT_JOB."""
import json
import os
import sys
import traceback

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore, QtGui

job = json.load(open(os.environ["SFIT_JOB"]))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
result = {"errors": []}


def write():
    with open(os.path.join(job["out"], "result_gui.json"), "w") as f:
        json.dump(result, f)


def step1():
    try:
        from sections import closed_sections
        result["workbenches"] = sorted(Gui.listWorkbenches())
        Gui.activateWorkbench("SfitWorkbench")
        result["command"] = "Sfit_FitSurface" in Gui.listCommands()
        doc = App.newDocument("sfit_fit")
        rings = closed_sections(doc)
        doc.recompute()
        Gui.Selection.clearSelection()
        for r in rings:
            Gui.Selection.addSelection(r)
        Gui.runCommand("Sfit_FitSurface")
        QtCore.QTimer.singleShot(1500, step2)
    except Exception:  # noqa: BLE001
        result["errors"].append(traceback.format_exc())
        finish()


def step2():
    try:
        doc = App.ActiveDocument
        obj = doc.getObject("SurfaceFit")
        dlg = Gui.Control.activeDialog()
        result["task_panel_open"] = bool(dlg)
        result["feature"] = obj is not None
        result["within"] = bool(obj.WithinTolerance)
        result["control_points"] = obj.ControlPoints
        result["data_points"] = obj.DataPoints
        vp = obj.ViewObject.Proxy
        result["view_provider"] = type(vp).__name__
        result["deviation_points_shown"] = vp.coords.point.getNum()
        result["deviation_switch"] = vp.switch.whichChild.getValue()
        result["worst_marker"] = list(vp.worst_coords.point[0].getValue())
        result["worst_point"] = list(obj.WorstPoint)
        # The panel refits at once: T = 0.5 mm absolute, then back to relative (the
        # screenshot's).
        panel = vp.panel
        panel.tol_abs.setValue(0.5)
        panel.mode.setCurrentIndex(1)  # Absolute: the signal applies it
        result["coarse"] = {"mode": obj.ToleranceMode, "T": list(obj.ToleranceUsed),
                            "control_points": obj.ControlPoints,
                             "within": bool(obj.WithinTolerance),
                             "report": panel.report.text()}
        panel.mode.setCurrentIndex(0)
        result["fine_again"] = obj.ControlPoints
        view = Gui.ActiveDocument.ActiveView
        view.viewIsometric()
        view.fitAll()
        QtCore.QTimer.singleShot(500, step3)
    except Exception:  # noqa: BLE001
        result["errors"].append(traceback.format_exc())
        finish()


def step3():
    try:
        mw = Gui.getMainWindow()
        mw.resize(1400, 860)
        docks = [d for d in mw.findChildren(QtGui.QDockWidget) if d.isVisible() and
                 d.findChild(QtGui.QTabWidget) is not None]  # the combo view with the panel
        if docks:
            mw.resizeDocks(docks[:1], [430], QtCore.Qt.Horizontal)
        QtGui.QApplication.processEvents()
        panel = None
        for w in mw.findChildren(QtGui.QWidget):
            if w.windowTitle() == "Fit surface (sfit)":
                panel = w
        result["panel_found"] = panel is not None
        if panel is not None:
            result["panel_text"] = [lb.text() for lb in panel.findChildren(QtGui.QLabel)]
        shot = mw.grab()
        mdi = mw.findChild(QtGui.QMdiArea)
        sub = mdi.activeSubWindow().widget()
        pos = sub.mapTo(mw, QtCore.QPoint(0, 0))
        img = os.path.join(job["out"], "view3d.png")
        Gui.ActiveDocument.ActiveView.saveImage(img, sub.width(), sub.height(), "Current")
        painter = QtGui.QPainter(shot)
        painter.drawImage(pos, QtGui.QImage(img))
        painter.end()
        shot.save(job["screenshot"])
        result["screenshot"] = job["screenshot"]
        result["size"] = [shot.width(), shot.height()]
    except Exception:  # noqa: BLE001
        result["errors"].append(traceback.format_exc())
    finish()


def finish():
    write()
    QtGui.QApplication.instance().quit()


QtCore.QTimer.singleShot(1000, step1)
