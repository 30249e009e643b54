"""Message boxes: an error shown in the Console and in a dialog."""
import FreeCAD
import FreeCADGui


def show_error(message, title="Contacts"):
    """An error in the Console and in a message box."""
    from PySide2 import QtWidgets
    FreeCAD.Console.PrintError(f"Contacts: {message}\n")
    QtWidgets.QMessageBox.warning(FreeCADGui.getMainWindow(), title, message)
