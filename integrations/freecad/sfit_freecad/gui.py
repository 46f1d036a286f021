"""The GUI part: the command "Fit surface", its task panel, and the view provider that
shows the data points coloured by |d|/T and the worst point. Needs FreeCAD's GUI."""
import os

import FreeCAD
import FreeCADGui as Gui
from PySide import QtCore, QtGui
from pivy import coin

from . import feature

COMMANDS = ["Sfit_FitSurface"]
ICON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Resources", "icons",
                    "sfit.svg")


def ratio_colour(r):
    """|d|/T to a colour: blue (0) through green (0.5) to red (1); magenta beyond T."""
    if r > 1.0:
        return (1.0, 0.0, 1.0)
    if r < 0.5:
        t = r / 0.5
        return (0.0, t, 1.0 - t)
    t = (r - 0.5) / 0.5
    return (t, 1.0 - t, 0.0)


class ViewProviderSurfaceFit:
    """Part's view of the face, plus the data points by |d|/T and a marker at the worst."""

    def __init__(self, vobj):
        vobj.Proxy = self
        self._add_properties(vobj)

    @staticmethod
    def _add_properties(vobj):
        if "ShowDeviation" not in vobj.PropertiesList:
            vobj.addProperty("App::PropertyBool", "ShowDeviation", "Sfit",
                             "Show the data points coloured by |d|/T (blue 0, green T/2, red T)")
            vobj.ShowDeviation = True
        if "DeviationPointSize" not in vobj.PropertiesList:
            vobj.addProperty("App::PropertyFloat", "DeviationPointSize", "Sfit",
                             "Size of the data points in pixels")
            vobj.DeviationPointSize = 5.0

    def attach(self, vobj):
        self.Object = vobj.Object
        self._add_properties(vobj)
        self.switch = coin.SoSwitch()
        sep = coin.SoSeparator()
        self.coords = coin.SoCoordinate3()
        self.material = coin.SoMaterial()
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_VERTEX
        self.style = coin.SoDrawStyle()
        self.style.pointSize = vobj.DeviationPointSize
        self.points = coin.SoPointSet()
        sep.addChild(self.style)
        sep.addChild(binding)
        sep.addChild(self.material)
        sep.addChild(self.coords)
        sep.addChild(self.points)
        # The worst point: a big marker.
        worst = coin.SoSeparator()
        wmat = coin.SoMaterial()
        wmat.diffuseColor = (1.0, 0.0, 0.0)
        self.worst_coords = coin.SoCoordinate3()
        marker = coin.SoMarkerSet()
        marker.markerIndex = Gui.getMarkerIndex("CIRCLE_FILLED", 15)
        worst.addChild(wmat)
        worst.addChild(self.worst_coords)
        worst.addChild(marker)
        sep.addChild(worst)
        self.switch.addChild(sep)
        vobj.RootNode.addChild(self.switch)
        self._update(vobj.Object)

    def _update(self, obj):
        pts = [tuple(p) for p in getattr(obj, "DataPointList", [])]
        ratios = list(getattr(obj, "DeviationRatio", []))
        if not hasattr(self, "coords"):
            return
        self.coords.point.setNum(0)
        self.material.diffuseColor.setNum(0)
        if pts and len(pts) == len(ratios):
            self.coords.point.setValues(0, len(pts), pts)
            self.material.diffuseColor.setValues(0, len(pts), [ratio_colour(r) for r in ratios])
            self.worst_coords.point.setValues(0, 1, [tuple(obj.WorstPoint)])
        show = pts and getattr(obj.ViewObject, "ShowDeviation", True)
        self.switch.whichChild = 0 if show else -1

    def updateData(self, obj, prop):
        if prop in ("DeviationRatio", "DataPointList", "WorstPoint"):
            self._update(obj)

    def onChanged(self, vobj, prop):
        if prop in ("ShowDeviation",) and hasattr(self, "switch"):
            self._update(vobj.Object)
        if prop == "DeviationPointSize" and hasattr(self, "style"):
            self.style.pointSize = vobj.DeviationPointSize

    def getIcon(self):
        return ICON

    def claimChildren(self):
        return list(self.Object.Sources) if hasattr(self, "Object") else []

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        self.panel = TaskPanel(vobj.Object)
        Gui.Control.showDialog(self.panel)
        return True

    def unsetEdit(self, vobj, mode=0):
        self.panel = None
        Gui.Control.closeDialog()
        return True

    def doubleClicked(self, vobj):
        Gui.ActiveDocument.setEdit(vobj.Object.Name)
        return True

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


class TaskPanel:
    """Tolerance (absolute or relative), degree, closed directions, method, and the report.
    Every change refits at once (the feature recomputes), so the report is a live preview."""

    def __init__(self, obj):
        self.obj = obj
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Fit surface (sfit)")
        lay = QtGui.QFormLayout(self.form)
        self.sources = QtGui.QLabel()
        self.sources.setWordWrap(True)
        lay.addRow("Sources", self.sources)
        self.mode = QtGui.QComboBox()
        self.mode.addItems(feature.TOLERANCE_MODES)
        lay.addRow("Tolerance", self.mode)
        self.tol_abs = QtGui.QDoubleSpinBox()
        self.tol_abs.setDecimals(6)
        self.tol_abs.setRange(0.0, 1e9)
        self.tol_abs.setSuffix(" mm")
        lay.addRow("  absolute T", self.tol_abs)
        self.tol_rel = QtGui.QDoubleSpinBox()
        self.tol_rel.setDecimals(6)
        self.tol_rel.setRange(0.0, 1.0)
        self.tol_rel.setSingleStep(1e-4)
        lay.addRow("  relative T", self.tol_rel)
        self.degree = QtGui.QSpinBox()
        self.degree.setRange(1, 20)
        lay.addRow("Degree", self.degree)
        self.closed = QtGui.QComboBox()
        self.closed.addItems(feature.CLOSED_CHOICES)
        lay.addRow("Closed", self.closed)
        self.method = QtGui.QComboBox()
        self.method.addItems(feature.METHODS)
        lay.addRow("Method", self.method)
        self.parameters = QtGui.QComboBox()
        self.parameters.addItems(feature.PARAMETERS)
        lay.addRow("Parameters", self.parameters)
        self.report = QtGui.QLabel()
        self.report.setTextFormat(QtCore.Qt.RichText)
        self.report.setWordWrap(True)
        lay.addRow(self.report)
        self._load()
        for w in (self.mode, self.closed, self.method, self.parameters):
            w.currentIndexChanged.connect(self.apply)
        for w in (self.tol_abs, self.tol_rel, self.degree):
            w.editingFinished.connect(self.apply)

    def _load(self):
        o = self.obj
        self.sources.setText(", ".join([s.Label for s in o.Sources] +
                                       [f"{e[0].Label}.{n}" for e in o.SourceEdges
                                        for n in e[1]]) +
                             (("; " if o.Sources else "") + os.path.basename(o.SourceFile)
                              if o.SourceFile else ""))
        self.mode.setCurrentIndex(feature.TOLERANCE_MODES.index(o.ToleranceMode))
        self.tol_abs.setValue(o.Tolerance.Value)
        self.tol_rel.setValue(o.ToleranceRelative)
        self.degree.setValue(o.Degree)
        self.closed.setCurrentIndex(feature.CLOSED_CHOICES.index(o.Closed))
        self.method.setCurrentIndex(feature.METHODS.index(o.Method))
        self.parameters.setCurrentIndex(feature.PARAMETERS.index(o.Parameters))
        self.show_report()

    def show_report(self):
        o = self.obj
        if "Invalid" in o.State or "Error" in o.State:
            self.report.setText("<b style='color:#c00'>The fit failed:</b> see the report view")
            return
        t, d = o.ToleranceUsed, o.MaxDeviation
        ok = "<b style='color:#080'>yes</b>" if o.WithinTolerance else "<b style='color:#c00'>no</b>"
        w = o.WorstPoint
        self.report.setText(
            f"<b>Control points</b> {o.ControlPoints} &nbsp; ({o.Rows} rows, {o.DataPoints} points,"
            f" closed: {o.ClosedUsed})<br>"
            f"<b>T</b> ({t.x:.4g}, {t.y:.4g}, {t.z:.4g})<br>"
            f"<b>Largest deviation</b> ({d.x:.3g}, {d.y:.3g}, {d.z:.3g})<br>"
            f"<b>Within T</b> {ok}<br>"
            f"<b>Worst point</b> {o.WorstPlace} at ({w.x:.4g}, {w.y:.4g}, {w.z:.4g}),"
            f" the red marker<br>"
            "<small>points: blue 0, green T/2, red T (|d|/T)</small>")

    def apply(self, *args):
        o = self.obj
        o.ToleranceMode = self.mode.currentText()
        o.Tolerance = self.tol_abs.value()
        o.ToleranceRelative = self.tol_rel.value()
        o.Degree = self.degree.value()
        o.Closed = self.closed.currentText()
        o.Method = self.method.currentText()
        o.Parameters = self.parameters.currentText()
        o.Document.recompute()
        self.show_report()

    def accept(self):
        self.apply()
        Gui.ActiveDocument.resetEdit()
        return True

    def reject(self):
        Gui.ActiveDocument.resetEdit()
        return True

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Close)


def make_view_provider(obj):
    if obj.ViewObject is not None:
        ViewProviderSurfaceFit(obj.ViewObject)


class FitSurfaceCommand:
    """From the selected sketches, wires, edges, curves or point objects (in the order
    selected), or from a chosen .rows/.csv file when nothing is selected."""

    def GetResources(self):
        return {"Pixmap": ICON, "MenuText": "Fit surface",
                "ToolTip": "Fit one B-spline surface within a tolerance through the selected "
                           "sections or points (or a .rows/.csv file when nothing is selected)"}

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        sel, edges = [], []
        for s in Gui.Selection.getSelectionEx():
            subs = [n for n in s.SubElementNames if n.startswith("Edge")]
            if subs:  # picked edges: each a row
                edges += [(s.Object, n) for n in subs]
            else:
                sel.append(s.Object)
        source_file = ""
        if not sel and not edges:
            source_file, _ = QtGui.QFileDialog.getOpenFileName(
                Gui.getMainWindow(), "Rows of points", "", "Rows (*.rows *.srows *.csv)")
            if not source_file:
                return
        doc.openTransaction("Fit surface")
        obj = feature.create(doc, sel, source_file, edges=edges)
        make_view_provider(obj)
        doc.recompute()
        doc.commitTransaction()
        for s in sel:
            if s.ViewObject is not None and s.TypeId.startswith("Points::"):
                s.ViewObject.Visibility = False
        Gui.ActiveDocument.setEdit(obj.Name)


def register_commands():
    Gui.addCommand("Sfit_FitSurface", FitSurfaceCommand())
