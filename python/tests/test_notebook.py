"""The example notebook (examples/python/touchdown.ipynb) runs from top to bottom in a
Jupyter kernel of this environment, as a user opens it: a sweep, the stability map, the
report as data, a Python law's sweep and trace."""

from pathlib import Path

import nbformat
from nbclient import NotebookClient

from conftest import ROOT


def test_the_notebook_runs(tmp_path):
    path = ROOT / "examples" / "python" / "touchdown.ipynb"
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
    )
    client.execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # The two figures drew (inline PNGs), and the law's sweep shows its outcomes.
    pictures = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(pictures) == 2
    nbformat.write(notebook, tmp_path / "executed.ipynb")
