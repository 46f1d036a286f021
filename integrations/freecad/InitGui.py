# sfit workbench (GUI): the command "Fit surface". FreeCAD runs this file at start-up with the
# workbench folder on sys.path; the commands are registered when the workbench is activated.
import os

import FreeCADGui as Gui


class SfitWorkbench(Gui.Workbench):
    import sfit_freecad as _pkg

    MenuText = "sfit"
    ToolTip = "Fit one B-spline surface within a tolerance to sections or points (sfit)"
    Icon = os.path.join(os.path.dirname(_pkg.__file__), "..", "Resources", "icons", "sfit.svg")

    def Initialize(self):
        from sfit_freecad import gui
        gui.register_commands()
        self.appendToolbar("sfit", gui.COMMANDS)
        self.appendMenu("&sfit", gui.COMMANDS)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(SfitWorkbench())
