"""Lets one script of this folder use another's functions (the PLY, OBJ and
skeleton readers live in spacing-floor and render-mesh, whose names are not
module names)."""
import importlib.machinery
import importlib.util
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def script(name):
    """The script `name` of this folder, loaded as a module (its main() not run)."""
    loader = importlib.machinery.SourceFileLoader(name.replace("-", "_"), os.path.join(HERE, name))
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(loader.name, loader))
    loader.exec_module(module)
    return module
