"""The type hints of the extension module (touchdown/_touchdown.pyi) name what it has: each
class's methods and attributes beyond what every object has, and the module's names, no
more and no fewer."""

import ast
from pathlib import Path

import touchdown
from touchdown import _touchdown

STUB = Path(touchdown.__file__).with_name("_touchdown.pyi")


def stub():
    """The stub's public module names, and per class the names it declares."""
    names, classes = set(), {}
    for node in ast.parse(STUB.read_text()).body:
        if isinstance(node, ast.ClassDef):
            names.add(node.name)
            classes[node.name] = {
                n.name if isinstance(n, ast.FunctionDef) else n.target.id
                for n in node.body
                if isinstance(n, ast.FunctionDef)
                or (isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name))
            }
        elif isinstance(node, ast.FunctionDef):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return {n for n in names if not n.startswith("_")}, classes


def test_the_stub_names_what_the_module_has():
    names, classes = stub()
    assert names == {n for n in vars(_touchdown) if not n.startswith("_")}
    every_object = set(vars(object)) | {"__module__", "__weakref__", "__dict__"}
    for name, declared in classes.items():
        cls = getattr(_touchdown, name)
        has = {n for n in vars(cls) if n not in every_object}
        # What the class adds (`del s[key]` among them) is in the stub...
        assert has <= declared, f"{name}: not in the stub: {sorted(has - declared)}"
        # ... and the stub declares nothing the class lacks.
        assert declared <= set(dir(cls)), f"{name}: not in the class: {sorted(declared - set(dir(cls)))}"
