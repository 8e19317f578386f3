"""The teaching notebooks (``notebooks/*.ipynb``, issue 7).

Each notebook asserts its key results against the published tables in its own cells, so executing it from
top to bottom is a test: any error (a failed assert included) fails here.  They run in a Jupyter kernel started
from this very interpreter (a kernelspec written for ``sys.executable`` into a temporary directory: an installed
"python3" kernelspec may name a different ``python``).  The repository keeps them with the outputs of one
top-to-bottom run (``notebooks/store_outputs.py``), so that their pictures show without running them.
"""

import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK_DIR = ROOT / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))


@pytest.fixture(scope="module")
def kernel_spec_manager(tmp_path_factory):
    from ipykernel.kernelspec import write_kernel_spec
    from jupyter_client.kernelspec import KernelSpecManager

    kernels = tmp_path_factory.mktemp("kernels")
    write_kernel_spec(kernels / "python3")
    ksm = KernelSpecManager(kernel_dirs=[str(kernels)])
    assert ksm.get_kernel_spec("python3").argv[0] == sys.executable
    return ksm


def test_the_lessons_are_there():
    names = {p.name for p in NOTEBOOKS}
    assert {"igp_orientation.ipynb", "igp_position.ipynb", "dgp_3_cables.ipynb"} <= names
    listed = (NOTEBOOK_DIR / "README.md").read_text(encoding="utf-8")
    assert all(name in listed for name in names), "notebooks/README.md lists every notebook"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_stored_with_the_outputs_of_one_run(path):
    """Every code cell executed once, in order, in one kernel (execution counts 1, 2, ...), no error stored, and the
    notebooks that draw store their pictures."""
    nb = nbformat.read(path, as_version=4)
    nbformat.validate(nb)
    assert nb.metadata.get("kernelspec", {}).get("name") == "python3"
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code, "a notebook without code"
    assert [c.execution_count for c in code] == list(range(1, len(code) + 1)), \
        "stored outputs are not from one top-to-bottom run: python3 notebooks/store_outputs.py " + path.name
    assert not [o for c in code for o in c.outputs if o.output_type == "error"]
    draws = any("plot_" in c.source or "plt." in c.source for c in code)
    images = sum("image/png" in o.get("data", {}) for c in code for o in c.outputs)
    assert images > 0 or not draws, "a notebook that draws stores its pictures"
    assert any("assert " in c.source for c in code), "a lesson asserts its key results"


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_executes_without_error(path, kernel_spec_manager):
    from jupyter_client.manager import KernelManager
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    km = KernelManager(kernel_name="python3", kernel_spec_manager=kernel_spec_manager)
    client = NotebookClient(nb, km=km, timeout=300, allow_errors=False,
                            resources={"metadata": {"path": str(path.parent)}})
    client.execute()  # raises CellExecutionError on the first failing cell
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if o.output_type == "error"]
    assert not errors
